#include "throng/support/StopSignals.h"

#include <atomic>
#include <csignal>
#include <unistd.h>

namespace throng::support {
namespace {

std::atomic<int> g_signal{0};  // lock-free, so that the handler may write it
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void onStopSignal(int signal) {
    int none = 0;
    if (!g_signal.compare_exchange_strong(none, signal)) _exit(128 + signal);  // the second: at once (async-signal-safe)
}

}  // namespace

StopRequested::StopRequested(int signal) : std::runtime_error("stopped by " + StopSignals::name(signal)), signal_(signal) {}

void StopSignals::install() {
    struct sigaction action = {};
    action.sa_handler = onStopSignal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;  // a read or write under way goes on; the loop looks at the flag between frames
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
    std::signal(SIGXFSZ, SIG_IGN);
}

int StopSignals::received() { return g_signal.load(std::memory_order_relaxed); }

std::string StopSignals::name(int signal) {
    if (signal == SIGINT) return "SIGINT";
    if (signal == SIGTERM) return "SIGTERM";
    return "signal " + std::to_string(signal);
}

void StopSignals::throwIfStopped() {
    if (const int s = received()) throw StopRequested(s);
}

}  // namespace throng::support
