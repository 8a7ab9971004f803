// Result<T>: a value or a one-line error message (the "bad data" tier of docs/architecture.md).
// std::expected is C++23; this is the small subset we need, with the same spelling.
#pragma once

#include <string>
#include <utility>
#include <variant>

namespace shadowkit::core {

/// Whose the fix is: the input's (a value that is wrong anywhere) or the environment's (a
/// machine that cannot do what was asked: no GL 4.5, a driver limit, memory, a driver that
/// rejects a shader). Front ends report them differently (`shadowkit` exits 1 or 3).
/// Whose fault an error is: the input's, or the environment's (no OpenGL 4.5, a driver limit).
enum class ErrorKind { BadInput, Environment };

/// A one-line message naming the input, and whether the input or the environment is at fault.
struct Error {
    std::string message; ///< one line: names the input and what is wrong
    /// The option the error is about, as a stable dotted name ("lispsm.weight", "blur.radius";
    /// empty when none): front ends map it to their own spelling (a CLI flag, a UI field)
    /// instead of validating the same ranges again.
    std::string field;
    ErrorKind kind = ErrorKind::BadInput; ///< bad input (exit 1) or an environment that cannot (exit 3)
};

/// A value or an Error: what every fallible core call returns (std::expected-like, C++20).
template <class T>
class [[nodiscard]] Result {
public:
    Result(T value) : m_state(std::move(value)) {}     ///< a success
    Result(Error error) : m_state(std::move(error)) {} ///< a failure

    bool hasValue() const { return m_state.index() == 0; } ///< true on success
    explicit operator bool() const { return hasValue(); }  ///< hasValue()

    /// @name The value: only on success (std::bad_variant_access otherwise)
    ///@{
    T& value() & { return std::get<0>(m_state); }              ///< the value
    const T& value() const& { return std::get<0>(m_state); }   ///< the value
    T&& value() && { return std::get<0>(std::move(m_state)); } ///< the value, moved out
    T* operator->() { return &value(); }                       ///< the value's members
    const T* operator->() const { return &value(); }           ///< the value's members
    T& operator*() & { return value(); }                       ///< the value
    const T& operator*() const& { return value(); }            ///< the value
    ///@}

    /// @name The error: only on failure
    ///@{
    const std::string& error() const { return std::get<1>(m_state).message; } ///< its one-line message
    const Error& errorInfo() const { return std::get<1>(m_state); }           ///< message, field and kind
    ///@}

private:
    std::variant<T, Error> m_state;
};

/// Result<void> equivalent: an empty success or an error.
struct Ok {};
using Status = Result<Ok>;

inline Error makeError(std::string message) { return Error{std::move(message), {}}; }
/// An error of the machine, not the input (ErrorKind::Environment), optionally about a field
/// whose value this machine cannot honour (a map size beyond the driver's limit).
inline Error environmentError(std::string message, std::string field = {}) {
    return Error{std::move(message), std::move(field), ErrorKind::Environment};
}
/// "field: what" with the field recorded, e.g. fieldError("lispsm.weight", "must be > 0").
inline Error fieldError(std::string field, const std::string& what) {
    std::string message = field + ": " + what;
    return Error{std::move(message), std::move(field)};
}

} // namespace shadowkit::core
