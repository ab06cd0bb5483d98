// Progress of long computations, reported to whoever asked and to no terminal: the command line
// passes a callback that draws a bar (cli/progress_bar.h), the Python module one that checks for
// Ctrl-C, a library user their own or none. The callback can cancel the work.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>

namespace so {

struct ProgressUpdate {
    const std::string& stage;  // "primary rays", "shadow rays sun", "writing oracle.exr"
    uint64_t done = 0, total = 0;
};

// Called from any worker thread, one call at a time per stage, at most every
// Progress::kInterval and once when the stage is complete. Returning false cancels: the
// computation throws Cancelled soon after (within one tile of work per thread), leaving no
// partial result behind.
using ProgressCallback = std::function<bool(const ProgressUpdate&)>;

// What a cancelled computation throws.
class Cancelled : public std::runtime_error {
  public:
    Cancelled() : std::runtime_error("cancelled") {}
};

// One stage's counter. Thread-safe: workers call advance().
class Progress {
  public:
    static constexpr std::chrono::milliseconds kInterval{50};

    // An empty callback: counted, reported to no one, never cancelled.
    Progress(std::string stage, uint64_t total, ProgressCallback callback);
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    // Throws Cancelled once the callback has asked to cancel.
    void advance(uint64_t n);

  private:
    void report(uint64_t done);
    std::string stage_;
    uint64_t total_;
    ProgressCallback callback_;
    std::atomic<uint64_t> done_{0};
    std::atomic<bool> cancelled_{false};
    std::mutex mutex_;  // one callback at a time
    // When the callback was last called (steady clock ticks): read by workers without the lock.
    std::atomic<std::chrono::steady_clock::rep> lastReport_;
    bool finalReported_ = false;
};

}  // namespace so
