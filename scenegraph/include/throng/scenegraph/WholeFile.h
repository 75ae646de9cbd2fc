#pragma once
// Files written whole or not at all: a reader never sees half a file, and a full disk, a file-size
// limit or a signal mid-way leaves the previous file (or none), never a truncated one. Every file
// Throng writes in one piece (PNGs, summary.json, reports, atlases) goes through here.

#include <filesystem>
#include <string_view>

namespace throng {

/// Writes `bytes` to `path` whole: into a temporary file beside it, then renamed over it. Throws
/// std::runtime_error "PATH: cannot be written: REASON" (the system's reason: no space left, file
/// too large, permission denied), leaving no temporary file behind.
void writeWholeFile(const std::filesystem::path& path, std::string_view bytes);

}  // namespace throng
