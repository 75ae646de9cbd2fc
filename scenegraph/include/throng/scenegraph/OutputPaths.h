#pragma once
// Whether an output path can be written, asked before any work starts: the one check every tool and
// benchmark applies to its output options (--out, --vtk, --csv, --plots, ...), so that a run never
// computes for minutes and then fails to save. Nothing is created by the checks.

#include <filesystem>
#include <string>

namespace throng {

/// Why this process could not write the file `path`, or "" when it can: no name, a folder, a
/// folder that does not exist, or one it cannot write into (asked of the file system with a file
/// made and removed at once, so that read-only mounts and root's rights answer truly).
std::string problemWritingFile(const std::filesystem::path& path);

/// Why this process could not write into the folder `path`, or "" when it can: an existing folder
/// it can write into, or a new one whose nearest existing folder it can write into. Refuses a path
/// that is a file or lies below one.
std::string problemWritingFolder(const std::filesystem::path& path);

}  // namespace throng
