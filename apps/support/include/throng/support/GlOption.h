#pragma once
// --gl, the one option by which every tool that renders chooses its GL context (ContextFactory.h).

#include <string>

#include <CLI/CLI.hpp>

namespace throng::support {

/// Declares --gl auto|window|egl|osmesa on `app`, into `value` (default "auto").
void declareGlOption(CLI::App& app, std::string& value);

}  // namespace throng::support
