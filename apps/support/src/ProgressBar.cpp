#include "throng/support/ProgressBar.h"

#include <unistd.h>

#include <algorithm>

namespace throng::support {

ProgressBar::ProgressBar(std::string label, std::size_t total, bool shown)
    : label_(std::move(label)), total_(std::max<std::size_t>(total, 1)), terminal_(isatty(fileno(stderr)) != 0), shown_(shown) {}

void ProgressBar::update(std::size_t done, const std::string& detail) {
    if (!shown_) return;
    const double f = std::min(1.0, double(done) / double(total_));
    if (terminal_) {
        constexpr int kWidth = 30;
        const int filled = int(f * kWidth);
        std::fprintf(stderr, "\r%s [%s%s] %3d%% %s\033[K", label_.c_str(), std::string(std::size_t(filled), '#').c_str(),
                     std::string(std::size_t(kWidth - filled), ' ').c_str(), int(f * 100.0), detail.c_str());
        std::fflush(stderr);
    } else if (int tenth = int(f * 10.0); tenth > lastTenth_) {
        lastTenth_ = tenth;
        std::fprintf(stderr, "%s: %3d%% %s\n", label_.c_str(), tenth * 10, detail.c_str());
    }
}

void ProgressBar::phase(std::size_t done, const std::string& name) {
    if (shown_ && !terminal_ && name != phase_) {
        phase_ = name;
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        std::fprintf(stderr, "%s: %3d%% %s (at %.1f s)\n", label_.c_str(), int(100.0 * std::min(1.0, double(done) / double(total_))),
                     name.c_str(), seconds);
        lastTenth_ = int(10.0 * std::min(1.0, double(done) / double(total_)));
        return;
    }
    phase_ = name;
    update(done, name);
}

void ProgressBar::stop(std::size_t done, const std::string& detail) {
    if (!shown_) return;
    if (terminal_) {
        update(done, detail);
        std::fprintf(stderr, "\n");
    } else {
        std::fprintf(stderr, "%s: %3d%% %s\n", label_.c_str(), int(100.0 * std::min(1.0, double(done) / double(total_))), detail.c_str());
    }
}

void ProgressBar::finish(const std::string& detail) {
    update(total_, detail);
    if (terminal_ && shown_) std::fprintf(stderr, "\n");
}

}  // namespace throng::support
