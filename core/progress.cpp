#include "core/progress.h"

#include <algorithm>

namespace so {

using Clock = std::chrono::steady_clock;

Progress::Progress(std::string stage, uint64_t total, ProgressCallback callback)
    : stage_(std::move(stage)),
      total_(total),
      callback_(std::move(callback)),
      lastReport_(Clock::now().time_since_epoch().count()) {}

namespace {
bool due(const std::atomic<Clock::rep>& last) {
    return Clock::now() -
               Clock::time_point(Clock::duration(last.load(std::memory_order_relaxed))) >=
           Progress::kInterval;
}
}  // namespace

void Progress::advance(uint64_t n) {
    const uint64_t done = done_.fetch_add(n) + n;
    if (callback_) {
        if (done >= total_) {
            // The last report is never skipped: the caller sees the stage complete.
            std::lock_guard lock(mutex_);
            if (!finalReported_) {
                finalReported_ = true;
                report(done);
            }
        } else if (due(lastReport_)) {
            // A worker that finds another one reporting goes back to work instead of waiting.
            std::unique_lock lock(mutex_, std::try_to_lock);
            if (lock.owns_lock() && !finalReported_ && due(lastReport_)) report(done);
        }
    }
    if (cancelled_.load(std::memory_order_relaxed)) throw Cancelled();
}

void Progress::report(uint64_t done) {
    lastReport_ = Clock::now().time_since_epoch().count();
    if (!callback_(ProgressUpdate{stage_, std::min(done, total_), total_})) cancelled_ = true;
}

}  // namespace so
