#pragma once
// A growable array of plain values whose storage comes straight from the kernel as pages that take
// no memory until written. A crowd's per-frame arrays are indexed by actor for the whole scene, yet
// a process that shows only its share of the actors (a rank posing the walkers it steps) writes a
// few of them: elements appended unwritten (appendUnwritten) then cost it nothing, and growing the
// array moves its pages (mremap) instead of copying them, so that they stay untouched. Linux only.

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <span>
#include <type_traits>
#include <utility>

namespace throng {

namespace detail {
/// Maps `bytes` (a multiple of pageBytes()) of untouched, zero pages; throws std::bad_alloc.
void* mapPages(std::size_t bytes);
/// Grows or moves a mapping from mapPages to `newBytes`, keeping what was written and leaving the
/// rest untouched; throws std::bad_alloc (the old mapping then stays valid).
void* remapPages(void* pages, std::size_t oldBytes, std::size_t newBytes);
/// Returns a mapping from mapPages or remapPages to the kernel.
void unmapPages(void* pages, std::size_t bytes);
/// The kernel's page size.
std::size_t pageBytes();
}  // namespace detail

/// A contiguous array of `T` (trivially copyable): a vector that can grow by elements not yet
/// written, which read as zero bytes and occupy no memory until written.
template <class T>
class PagedArray {
    static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>,
                  "PagedArray holds plain values: its elements are created by writing their bytes");

public:
    PagedArray() = default;
    ~PagedArray() { release(); }
    /// A copy of `other` (its unwritten elements are written here as zero bytes).
    PagedArray(const PagedArray& other) { append(std::span<const T>(other.data(), other.size())); }
    /// Takes `other`'s pages; `other` is left empty.
    PagedArray(PagedArray&& other) noexcept { swap(other); }
    /// Becomes a copy of `other`.
    PagedArray& operator=(const PagedArray& other) {
        if (this != &other) {
            PagedArray copy(other);
            swap(copy);
        }
        return *this;
    }
    /// Takes `other`'s pages, giving back its own; `other` is left empty.
    PagedArray& operator=(PagedArray&& other) noexcept {
        PagedArray moved(std::move(other));
        swap(moved);
        return *this;
    }

    /// Number of elements.
    std::size_t size() const { return size_; }
    /// Whether there is none.
    bool empty() const { return size_ == 0; }
    /// First element (null while nothing was ever stored).
    T* data() { return data_; }
    /// First element, read-only.
    const T* data() const { return data_; }
    /// Element `i` (< size(), unchecked).
    T& operator[](std::size_t i) { return data_[i]; }
    /// Element `i` (< size(), unchecked), read-only.
    const T& operator[](std::size_t i) const { return data_[i]; }
    /// First element, for ranges and spans.
    T* begin() { return data_; }
    /// One past the last element.
    T* end() { return data_ + size_; }
    /// First element, read-only.
    const T* begin() const { return data_; }
    /// One past the last element, read-only.
    const T* end() const { return data_ + size_; }

    /// Appends `value`.
    void push_back(const T& value) {
        const T copy = value;  // `value` may be an element, which growing moves
        reserve(size_ + 1);
        std::memcpy(static_cast<void*>(data_ + size_), &copy, sizeof(T));
        ++size_;
    }
    /// Appends `values`.
    void append(std::span<const T> values) {
        if (values.empty()) return;
        reserve(size_ + values.size());
        std::memcpy(static_cast<void*>(data_ + size_), values.data(), values.size_bytes());
        size_ += values.size();
    }
    /// Appends `count` elements that read as zero bytes and take no memory until written.
    void appendUnwritten(std::size_t count) {
        reserve(size_ + count);
        size_ += count;
    }
    /// Room for `count` elements without moving. Elements beyond size() are never written (the
    /// array never shrinks), which is what keeps appendUnwritten's elements zero.
    void reserve(std::size_t count) {
        if (count <= capacity_) return;
        const std::size_t page = detail::pageBytes();
        const std::size_t wanted = std::max(count, capacity_ + capacity_ / 2);
        const std::size_t bytes = (wanted * sizeof(T) + page - 1) / page * page;
        data_ = static_cast<T*>(data_ ? detail::remapPages(data_, mappedBytes_, bytes) : detail::mapPages(bytes));
        mappedBytes_ = bytes;
        capacity_ = bytes / sizeof(T);
    }
    /// Exchanges the contents of two arrays.
    void swap(PagedArray& other) noexcept {
        std::swap(data_, other.data_);
        std::swap(size_, other.size_);
        std::swap(capacity_, other.capacity_);
        std::swap(mappedBytes_, other.mappedBytes_);
    }

private:
    void release() {
        if (data_) detail::unmapPages(data_, mappedBytes_);
        data_ = nullptr, size_ = capacity_ = mappedBytes_ = 0;
    }

    T* data_ = nullptr;
    std::size_t size_ = 0;
    std::size_t capacity_ = 0;
    std::size_t mappedBytes_ = 0;
};

}  // namespace throng
