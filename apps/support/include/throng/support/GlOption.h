#pragma once
// --gl, the one option by which every tool that renders chooses its GL context (ContextFactory.h).

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

namespace throng::support {

/// Declares --gl auto|window|egl|osmesa on `app`, into `value` (default "auto"), and --gl-info, which
/// prints headlessGlReport() and exits 0. A tool that only renders off-screen passes window = false
/// (then auto|egl|osmesa).
void declareGlOption(CLI::App& app, std::string& value, bool window = true);

/// A headless context asked for by name (--gl egl or osmesa) is tried before minutes of work: when it
/// cannot be made, prints "program: --gl KIND: what is missing" and returns 2 (the usage exit code).
/// std::nullopt when it can, or for auto and window.
std::optional<int> refuseUnavailableGl(const std::string& program, const std::string& gl);

/// What this machine offers for headless GL, as --gl-info prints it: the EGL devices listed, then for
/// --gl egl, --gl osmesa and auto (headless) the context each gives (kind, vendor, renderer, version)
/// or why it cannot be made. Makes and drops a small context of each kind.
std::string headlessGlReport();

}  // namespace throng::support
