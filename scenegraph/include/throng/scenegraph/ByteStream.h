#pragma once
// Raw bytes of plain values, for messages between processes of one build (the ranks of a run):
// a writer that appends them and a reader that takes them back, checking that the bytes hold what
// it reads and naming what was cut short when they do not. No byte order or versioning of its own:
// both sides are the same program.

#include <cstddef>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace throng {

/// Appends plain values to a byte vector.
class ByteWriter {
public:
    /// Appends to `out` (which must outlive the writer).
    explicit ByteWriter(std::vector<std::byte>& out) : out_(out) {}
    /// Appends `n` bytes from `p`.
    void putBytes(const void* p, std::size_t n) {
        const std::size_t at = out_.size();
        out_.resize(at + n);
        if (n) std::memcpy(out_.data() + at, p, n);
    }
    /// Appends the bytes of `value`.
    template <class T>
    void put(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        putBytes(&value, sizeof(T));
    }
    /// Appends the bytes of every value of `values`.
    template <class T>
    void putSpan(std::span<const T> values) {
        static_assert(std::is_trivially_copyable_v<T>);
        putBytes(values.data(), values.size_bytes());
    }
    /// Bytes in the vector so far.
    std::size_t size() const { return out_.size(); }

private:
    std::vector<std::byte>& out_;
};

/// Reads back what a ByteWriter wrote. Errors are std::invalid_argument naming the reader's
/// `source` (who reads, for the message), where the bytes end and what they cut short.
class ByteReader {
public:
    /// Reads `bytes` (which must outlive the reader) on behalf of `source`.
    ByteReader(std::span<const std::byte> bytes, std::string source) : bytes_(bytes), source_(std::move(source)) {}
    /// Copies the next `n` bytes into `into`; throws if fewer are left (`what`: what they hold).
    void read(void* into, std::size_t n, std::string_view what) {
        require(n, what);
        if (n) std::memcpy(into, bytes_.data() + at_, n);
        at_ += n;
    }
    /// The next value of type T.
    template <class T>
    T get(std::string_view what) {
        static_assert(std::is_trivially_copyable_v<T>);
        T value;
        read(&value, sizeof(T), what);
        return value;
    }
    /// The next `n` bytes, in place (throws as read() does).
    std::span<const std::byte> take(std::size_t n, std::string_view what) {
        require(n, what);
        const std::span<const std::byte> taken = bytes_.subspan(at_, n);
        at_ += n;
        return taken;
    }
    /// Skips `n` bytes (throws as read() does).
    void skip(std::size_t n, std::string_view what) {
        require(n, what);
        at_ += n;
    }
    /// Throws unless `n` more bytes are left.
    void require(std::size_t n, std::string_view what) const {
        if (bytes_.size() - at_ < n)
            throw std::invalid_argument(source_ + ": the bytes end at " + std::to_string(bytes_.size()) + " inside " + std::string(what));
    }
    /// Bytes read so far.
    std::size_t offset() const { return at_; }
    /// Bytes not read yet.
    std::size_t remaining() const { return bytes_.size() - at_; }
    /// Who reads (the start of every error message).
    const std::string& source() const { return source_; }

private:
    std::span<const std::byte> bytes_;
    std::size_t at_ = 0;
    std::string source_;
};

}  // namespace throng
