// Progress on stderr for long runs: a bar redrawn in place on a terminal, otherwise one line every
// few seconds (so CI logs show life without filling up), with the time so far and, once something
// is done, an ETA from the rate so far. Thread-safe: workers call advance().
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace so {

class Progress {
  public:
    Progress(std::string label, uint64_t total, bool enabled = true);
    ~Progress();  // finishes the line if anything was drawn
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    void advance(uint64_t n);
    // Text after the bar, e.g. "2 failed, 2 running" (a sweep); shown from the next draw.
    void setNote(std::string note);

  private:
    void draw(uint64_t done, bool final);
    std::string label_;
    uint64_t total_;
    bool enabled_, tty_;
    std::atomic<uint64_t> done_{0};
    std::mutex mutex_;
    std::chrono::steady_clock::time_point start_, lastDraw_;
    bool drawn_ = false;
    std::string note_;  // guarded by mutex_
};

}  // namespace so
