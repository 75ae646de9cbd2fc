#include "throng/scenegraph/WholeFile.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <stdexcept>
#include <string>
#include <unistd.h>

namespace throng {
namespace {

[[noreturn]] void cannotWrite(const std::filesystem::path& path, int error) {
    throw std::runtime_error(path.string() + ": cannot be written: " + std::strerror(error));
}

}  // namespace

void writeWholeFile(const std::filesystem::path& path, std::string_view bytes) {
    // Beside the file, so that the rename stays on one file system; hidden, and named by process so
    // that two programs writing the same file never share a temporary.
    std::filesystem::path temporary = path;
    temporary.replace_filename("." + path.filename().string() + ".partial-" + std::to_string(::getpid()));
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) cannotWrite(path, errno);
    std::size_t done = 0;
    int error = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            error = n < 0 ? errno : ENOSPC;
            break;
        }
        done += std::size_t(n);
    }
    if (::close(fd) != 0 && error == 0) error = errno;  // a delayed write error (NFS, quotas) shows here
    if (error == 0 && ::rename(temporary.c_str(), path.c_str()) != 0) error = errno;
    if (error != 0) {
        ::unlink(temporary.c_str());
        cannotWrite(path, error);
    }
}

}  // namespace throng
