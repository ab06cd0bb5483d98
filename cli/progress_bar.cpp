#include "cli/progress_bar.h"

#include <unistd.h>
#include <algorithm>
#include <cstdio>

namespace so {

using Clock = std::chrono::steady_clock;

ProgressBar::ProgressBar(bool enabled)
    : enabled_(enabled), tty_(isatty(STDERR_FILENO) != 0), start_(Clock::now()) {}

ProgressBar::~ProgressBar() {
    std::lock_guard lock(mutex_);
    if (drawn_ && done_ < total_) draw(true);
}

ProgressCallback ProgressBar::callback() {
    if (!enabled_) return {};
    return [this](const ProgressUpdate& u) {
        update(u.stage, u.done, u.total);
        return true;
    };
}

void ProgressBar::update(const std::string& stage, uint64_t done, uint64_t total) {
    if (!enabled_) return;
    std::lock_guard lock(mutex_);
    const auto now = Clock::now();
    if (stage != stage_) {
        if (drawn_ && done_ < total_) draw(true);  // a stage left unfinished ends its line
        stage_ = stage;
        start_ = now;
        drawn_ = false;
    }
    done_ = done;
    total_ = total;
    const bool final = done >= total;
    // Short stages stay quiet: a bar after one second on a terminal; otherwise a first line after
    // two seconds, then one every five. A stage that was drawn is drawn complete too.
    if (final) {
        if (drawn_) draw(true);
        return;
    }
    if (now - start_ < (tty_ ? std::chrono::seconds(1) : std::chrono::seconds(2))) return;
    const auto interval = tty_ ? std::chrono::milliseconds(100) : std::chrono::milliseconds(5000);
    if (drawn_ && now - lastDraw_ < interval) return;
    lastDraw_ = now;
    draw(false);
}

void ProgressBar::setNote(std::string note) {
    std::lock_guard lock(mutex_);
    note_ = std::move(note);
}

namespace {

// "42s", "3m07s", "2h05m": what an ETA needs, not more.
std::string duration(double seconds) {
    char text[32];
    const long s = long(seconds + 0.5);
    if (s < 60)
        std::snprintf(text, sizeof text, "%lds", s);
    else if (s < 3600)
        std::snprintf(text, sizeof text, "%ldm%02lds", s / 60, s % 60);
    else
        std::snprintf(text, sizeof text, "%ldh%02ldm", s / 3600, s / 60 % 60);
    return text;
}

}  // namespace

void ProgressBar::draw(bool final) {
    const double frac = total_ ? std::min(1.0, double(done_) / double(total_)) : 1.0;
    const double secs = std::chrono::duration<double>(Clock::now() - start_).count();
    std::string tail;
    if (done_ > 0 && done_ < total_) tail += " ETA " + duration(secs / frac - secs);
    if (!note_.empty()) tail += (tty_ ? "  " : "; ") + note_;
    if (tty_) {
        const int width = 30;
        const int filled = int(frac * width + 0.5);
        // \033[K: a shorter line than the last leaves none of it behind.
        std::fprintf(stderr, "\r%s [%.*s%*s] %5.1f%% %6.1fs%s\033[K", stage_.c_str(), filled,
                     "==============================", width - filled, "", 100.0 * frac, secs,
                     tail.c_str());
        if (final) std::fputc('\n', stderr);
    } else {
        std::fprintf(stderr, "%s: %5.1f%% after %.1fs%s\n", stage_.c_str(), 100.0 * frac, secs,
                     tail.c_str());
    }
    std::fflush(stderr);
    drawn_ = true;
}

}  // namespace so
