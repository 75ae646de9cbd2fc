#include "throng/scenegraph/OutputPaths.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace throng {
namespace {

namespace fs = std::filesystem;

std::string inQuotes(const std::string& s) { return "'" + s + "'"; }

// Why this process cannot write a new file into `folder` (a file made and removed at once), or "".
std::string cannotWriteInto(const fs::path& folder) {
    const fs::path probe = folder / (".throng-write-check-" + std::to_string(::getpid()));
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0) return "cannot write into the folder " + inQuotes(folder.string()) + ": " + std::strerror(errno);
    ::close(fd);
    ::unlink(probe.c_str());
    return {};
}

}  // namespace

std::string problemWritingFile(const fs::path& path) {
    std::error_code ec;
    if (path.empty()) return "no file named";
    if (fs::is_directory(path, ec)) return inQuotes(path.string()) + " is a folder";
    const fs::path folder = path.parent_path();
    if (!folder.empty() && !fs::is_directory(folder, ec)) return "no such folder: " + inQuotes(folder.string());
    return cannotWriteInto(folder.empty() ? fs::path(".") : folder);
}

std::string problemWritingFolder(const fs::path& path) {
    std::error_code ec;
    if (path.empty()) return "no folder named";
    if (fs::exists(path, ec)) {
        if (!fs::is_directory(path, ec)) return inQuotes(path.string()) + " is a file, not a folder";
        return cannotWriteInto(path);
    }
    // Nothing is made here (another run may be checking the same folder at once): the nearest
    // folder that exists must be one this process can write into.
    fs::path above = path.lexically_normal();
    if (above.filename().empty()) above = above.parent_path();
    do above = above.parent_path();
    while (!above.empty() && !fs::exists(above, ec));
    if (above.empty()) above = ".";
    if (!fs::is_directory(above, ec)) return "cannot create the folder " + inQuotes(path.string()) + ": " + inQuotes(above.string()) + " is a file";
    if (std::string problem = cannotWriteInto(above); !problem.empty()) return "cannot create the folder " + inQuotes(path.string()) + ": " + problem;
    return {};
}

}  // namespace throng
