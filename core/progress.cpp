#include "core/progress.h"

#include <unistd.h>
#include <algorithm>
#include <cstdio>
#include <string>

namespace so {

using Clock = std::chrono::steady_clock;

Progress::Progress(std::string label, uint64_t total, bool enabled)
    : label_(std::move(label)),
      total_(total),
      enabled_(enabled),
      tty_(isatty(STDERR_FILENO) != 0),
      start_(Clock::now()),
      lastDraw_(start_) {}

Progress::~Progress() {
    if (drawn_) draw(done_.load(), true);
}

void Progress::advance(uint64_t n) {
    uint64_t done = done_.fetch_add(n) + n;
    if (!enabled_) return;
    auto now = Clock::now();
    // Short runs stay quiet: a bar after one second on a terminal; otherwise a first line after
    // two seconds, then one every five.
    auto sinceStart = now - start_;
    if (sinceStart < (tty_ ? std::chrono::seconds(1) : std::chrono::seconds(2))) return;
    std::unique_lock lock(mutex_, std::try_to_lock);
    if (!lock.owns_lock()) return;
    auto interval = tty_ ? std::chrono::milliseconds(100) : std::chrono::milliseconds(5000);
    if (drawn_ && now - lastDraw_ < interval) return;
    lastDraw_ = now;
    draw(done, false);
}

void Progress::setNote(std::string note) {
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

void Progress::draw(uint64_t done, bool final) {
    double frac = total_ ? std::min(1.0, double(done) / double(total_)) : 1.0;
    double secs = std::chrono::duration<double>(Clock::now() - start_).count();
    std::string tail;
    if (done > 0 && done < total_) tail += " ETA " + duration(secs / frac - secs);
    if (!note_.empty()) tail += (tty_ ? "  " : "; ") + note_;
    if (tty_) {
        const int width = 30;
        int filled = int(frac * width + 0.5);
        // \033[K: a shorter line than the last leaves none of it behind.
        std::fprintf(stderr, "\r%s [%.*s%*s] %5.1f%% %6.1fs%s\033[K", label_.c_str(), filled,
                     "==============================", width - filled, "", 100.0 * frac, secs,
                     tail.c_str());
        if (final) std::fputc('\n', stderr);
    } else {
        std::fprintf(stderr, "%s: %5.1f%% after %.1fs%s\n", label_.c_str(), 100.0 * frac, secs,
                     tail.c_str());
    }
    std::fflush(stderr);
    drawn_ = true;
}

}  // namespace so
