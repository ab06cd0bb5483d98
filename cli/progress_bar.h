// The command line's progress display on stderr, fed by the libraries' progress callbacks
// (core/progress.h): a bar redrawn in place on a terminal, otherwise one line every few seconds
// (so CI logs show life without filling up), with the time so far and, once something is done, an
// ETA from the rate so far. Short stages stay quiet.
#pragma once

#include <chrono>
#include <mutex>
#include <string>

#include "core/progress.h"

namespace so {

class ProgressBar {
  public:
    explicit ProgressBar(bool enabled = true);
    ~ProgressBar();  // finishes a line left open
    ProgressBar(const ProgressBar&) = delete;
    ProgressBar& operator=(const ProgressBar&) = delete;

    // For a library's options; empty when the bar is disabled. Never cancels. The bar must
    // outlive the computation.
    ProgressCallback callback();
    // Thread-safe. A new stage name finishes the previous stage's line.
    void update(const std::string& stage, uint64_t done, uint64_t total);
    // Text after the bar, e.g. "2 failed, 2 running" (a sweep); shown from the next draw.
    void setNote(std::string note);

  private:
    void draw(bool final);
    bool enabled_, tty_;
    std::mutex mutex_;
    std::string stage_, note_;
    uint64_t done_ = 0, total_ = 0;
    std::chrono::steady_clock::time_point start_, lastDraw_;
    bool drawn_ = false;  // something drawn this stage
};

}  // namespace so
