#pragma once
// SIGINT and SIGTERM turned into a request to stop, so that a long run ends cleanly: the program
// finishes the frame in progress, closes its files whole and exits 130 (SIGINT) or 143 (SIGTERM).
// A second signal exits at once with the same code. SIGXFSZ is ignored, so that a file-size limit
// is an error a write reports, not a crash.

#include <stdexcept>
#include <string>

namespace throng::support {

/// Thrown by StopSignals::throwIfStopped: the run was asked to stop before it had anything to keep.
class StopRequested : public std::runtime_error {
public:
    /// For signal `signal`.
    explicit StopRequested(int signal);
    /// The signal that asked.
    int signal() const { return signal_; }

private:
    int signal_;
};

/// The process's stop requests (one set of handlers per process).
class StopSignals {
public:
    /// Installs the handlers (SIGINT, SIGTERM; SIGXFSZ ignored). Call once, early in main.
    static void install();
    /// The signal that asked to stop, or 0.
    static int received();
    /// The exit code for a run stopped by `signal`: 128 + signal (130 for SIGINT, 143 for SIGTERM).
    static int exitCode(int signal) { return 128 + signal; }
    /// "SIGINT", "SIGTERM" or "signal N".
    static std::string name(int signal);
    /// Throws StopRequested when a signal asked to stop (for long set-up work with nothing to keep).
    static void throwIfStopped();
};

}  // namespace throng::support
