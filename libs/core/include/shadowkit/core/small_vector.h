// A vector that keeps its first N elements inline: no heap allocation until it grows past
// N. For the per-frame geometry of the set-up (bodies of a few dozen face corners, a few
// shadow views), so that computing a shadow set-up does not touch the allocator in the
// usual case, and stays correct (spilling to the heap) in any other.
//
// Only for plain values (trivially copyable and destructible: points, planes, matrices): the
// inline storage is raw bytes that no constructor touches, so making or copying a vector costs
// what its elements in use cost, not its capacity (a set-up's 16 inline views are 11 KB).
#pragma once

#include <cstddef>
#include <cstring>
#include <initializer_list>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace shadowkit::core {

/// A vector holding up to N elements inline, so a set-up allocates no memory (spills to the heap beyond).
template <class T, size_t N>
class SmallVector {
    static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>,
                  "SmallVector holds plain values: its inline storage is copied as bytes");

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
        if (m_heap.empty() && m_size > 0) std::memcpy(m_inline, other.m_inline, m_size * sizeof(T));
        pointAtStorage();
        return *this;
    }
    SmallVector& operator=(SmallVector&& other) noexcept {
        if (this == &other) return *this;
        m_size = other.m_size;
        m_heap = std::move(other.m_heap);
        if (m_heap.empty() && m_size > 0) std::memcpy(m_inline, other.m_inline, m_size * sizeof(T));
        pointAtStorage();
        other.m_size = 0;
        other.m_heap.clear();
        other.pointAtStorage();
        return *this;
    }

    size_t size() const { return m_size; }
    bool empty() const { return m_size == 0; }
    T* data() { return m_data; }
    const T* data() const { return m_data; }
    T* begin() { return m_data; }
    T* end() { return m_data + m_size; }
    const T* begin() const { return m_data; }
    const T* end() const { return m_data + m_size; }
    T& operator[](size_t i) { return m_data[i]; }
    const T& operator[](size_t i) const { return m_data[i]; }
    T& front() { return m_data[0]; }
    T& back() { return m_data[m_size - 1]; }
    const T& front() const { return m_data[0]; }
    const T& back() const { return m_data[m_size - 1]; }

    void push_back(const T& value) {
        if (m_size < m_inlineLeft) { // inline and room left: the per-frame path, one compare
            ::new (static_cast<void*>(m_data + m_size)) T(value);
            ++m_size;
            return;
        }
        if (m_heap.empty()) { // spill: every element moves to the heap from now on
            m_heap.reserve(2 * N);
            m_heap.assign(m_data, m_data + m_size);
        }
        m_heap.push_back(value);
        ++m_size;
        pointAtStorage();
    }
    void clear() {
        m_size = 0;
        m_heap.clear();
        pointAtStorage();
    }
    /// Drops the elements from index `count` on (a no-op when `count >= size()`).
    void truncate(size_t count) {
        if (count >= m_size) return;
        m_size = count;
        if (!m_heap.empty()) m_heap.resize(count);
        pointAtStorage();
    }

    ///@}
private:
    // The elements live inline until they outgrow it, then in m_heap; m_data points at
    // whichever holds them, and m_inlineLeft is N while inline, 0 once spilled (so push_back's
    // fast path is one compare and an access one load).
    void pointAtStorage() {
        const bool spilled = !m_heap.empty();
        m_data = spilled ? m_heap.data() : reinterpret_cast<T*>(m_inline);
        m_inlineLeft = spilled ? 0 : N;
    }

    alignas(T) unsigned char m_inline[N * sizeof(T)]; // raw: no element is made until pushed
    T* m_data = reinterpret_cast<T*>(m_inline);
    size_t m_size = 0;
    size_t m_inlineLeft = N;
    std::vector<T> m_heap; ///< holds every element once the inline storage has overflowed
};

} // namespace shadowkit::core
