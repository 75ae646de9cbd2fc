#pragma once
// A progress bar on the terminal for long runs: redrawn in place on a terminal, a line every ten
// per cent otherwise (logs, CI).

#include <chrono>
#include <cstdio>
#include <string>

namespace throng::support {

/// Progress of `total` steps, written to stderr.
class ProgressBar {
public:
    /// A bar for `total` steps labelled `label`; one not `shown` writes nothing (every MPI rank but
    /// the first, say, whose bars would interleave with its).
    ProgressBar(std::string label, std::size_t total, bool shown = true);
    /// Shows that `done` steps are done, with `detail` after the bar.
    void update(std::size_t done, const std::string& detail = {});
    /// Shows that `done` steps are done in phase `name`. Off a terminal (logs, CI) each new phase
    /// gets its own line with the seconds since the bar began, so that long set-up work shows
    /// where its time goes.
    void phase(std::size_t done, const std::string& name);
    /// Ends the bar (a final newline on a terminal).
    void finish(const std::string& detail = {});
    /// Ends the bar where it stands, `done` of the total (a run stopped early), with `detail`.
    void stop(std::size_t done, const std::string& detail);

private:
    std::string label_;
    std::size_t total_;
    bool terminal_;
    bool shown_;
    int lastTenth_ = -1;
    std::string phase_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace throng::support
