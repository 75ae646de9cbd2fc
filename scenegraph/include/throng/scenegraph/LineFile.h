#pragma once
// A file that grows by whole lines, such as stats.csv: each line reaches the file in one write, and
// a line that cannot be written whole (disk full, file-size limit) is taken back, so the file ends
// at the last whole line whatever stops the program.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace throng {

/// A text file written line by line, always ending at a whole line.
class LineFile {
public:
    /// Creates (or empties) `path`. Throws std::runtime_error "PATH: cannot be written: REASON".
    explicit LineFile(std::filesystem::path path);
    ~LineFile();
    LineFile(const LineFile&) = delete;
    LineFile& operator=(const LineFile&) = delete;

    /// Appends `lines` (one or more lines, each ending in '\n') in one write. Throws
    /// std::runtime_error naming the file and the reason when they cannot be written whole; the
    /// file then ends where it ended before.
    void append(std::string_view lines);
    /// The file's path.
    const std::filesystem::path& path() const { return path_; }
    /// Bytes written so far (whole lines only).
    std::uint64_t size() const { return size_; }

private:
    std::filesystem::path path_;
    int fd_ = -1;
    std::uint64_t size_ = 0;
};

}  // namespace throng
