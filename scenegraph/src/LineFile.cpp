#include "throng/scenegraph/LineFile.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <stdexcept>
#include <unistd.h>

namespace throng {
namespace {

[[noreturn]] void cannotWrite(const std::filesystem::path& path, int error) {
    throw std::runtime_error(path.string() + ": cannot be written: " + std::strerror(error));
}

}  // namespace

LineFile::LineFile(std::filesystem::path path) : path_(std::move(path)) {
    fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd_ < 0) cannotWrite(path_, errno);
}

LineFile::~LineFile() {
    if (fd_ >= 0) ::close(fd_);
}

void LineFile::append(std::string_view lines) {
    std::size_t done = 0;
    while (done < lines.size()) {
        const ssize_t n = ::pwrite(fd_, lines.data() + done, lines.size() - done, off_t(size_ + done));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const int error = n < 0 ? errno : ENOSPC;
            // Take the partial line back (nothing more can be done if even that fails).
            [[maybe_unused]] const int truncated = ::ftruncate(fd_, off_t(size_));
            cannotWrite(path_, error);
        }
        done += std::size_t(n);
    }
    size_ += lines.size();
}

}  // namespace throng
