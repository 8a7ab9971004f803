// A vector that keeps its first N elements inline: no heap allocation until it grows past
// N. For the per-frame geometry of the set-up (polygons of a few dozen points, bodies of a
// few dozen faces), so that computing a shadow set-up does not touch the allocator in the
// usual case, and stays correct (spilling to the heap) in any other.
#pragma once

#include <array>
#include <cstddef>
#include <initializer_list>
#include <utility>
#include <vector>

namespace shadowkit::core {

/// A vector holding up to N elements inline, so a set-up allocates no memory (spills to the heap beyond).
template <class T, size_t N>
class SmallVector {
public:
    /// @name The part of std::vector's interface set-ups use
    ///@{
    using value_type = T;
    using iterator = T*;
    using const_iterator = const T*;

    SmallVector() = default;
    SmallVector(std::initializer_list<T> values) {
        for (const T& v : values) push_back(v);
    }
    /// Copies and moves touch the elements in use only, not the whole inline capacity.
    SmallVector(const SmallVector& other) { *this = other; }
    SmallVector(SmallVector&& other) noexcept { *this = std::move(other); }
    SmallVector& operator=(const SmallVector& other) {
        if (this == &other) return *this;
        m_size = other.m_size;
        m_heap = other.m_heap;
        if (m_heap.empty())
            for (size_t i = 0; i < m_size; ++i) m_inline[i] = other.m_inline[i];
        return *this;
    }
    SmallVector& operator=(SmallVector&& other) noexcept {
        if (this == &other) return *this;
        m_size = other.m_size;
        m_heap = std::move(other.m_heap);
        if (m_heap.empty())
            for (size_t i = 0; i < m_size; ++i) m_inline[i] = std::move(other.m_inline[i]);
        other.m_size = 0;
        other.m_heap.clear();
        return *this;
    }

    size_t size() const { return m_size; }
    bool empty() const { return m_size == 0; }
    T* data() { return m_heap.empty() ? m_inline.data() : m_heap.data(); }
    const T* data() const { return m_heap.empty() ? m_inline.data() : m_heap.data(); }
    T* begin() { return data(); }
    T* end() { return data() + m_size; }
    const T* begin() const { return data(); }
    const T* end() const { return data() + m_size; }
    T& operator[](size_t i) { return data()[i]; }
    const T& operator[](size_t i) const { return data()[i]; }
    T& front() { return data()[0]; }
    T& back() { return data()[m_size - 1]; }
    const T& front() const { return data()[0]; }
    const T& back() const { return data()[m_size - 1]; }

    void push_back(T value) {
        if (m_heap.empty() && m_size < N) {
            m_inline[m_size++] = std::move(value);
            return;
        }
        if (m_heap.empty()) { // spill: every element moves to the heap from now on
            m_heap.reserve(2 * N);
            for (size_t i = 0; i < m_size; ++i) m_heap.push_back(std::move(m_inline[i]));
        }
        m_heap.push_back(std::move(value));
        ++m_size;
    }
    void clear() {
        m_size = 0;
        m_heap.clear();
    }

    ///@}
private:
    std::array<T, N> m_inline;
    size_t m_size = 0;
    std::vector<T> m_heap; ///< holds every element once the inline storage has overflowed
};

} // namespace shadowkit::core
