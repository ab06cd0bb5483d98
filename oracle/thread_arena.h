// The oracle's threads: a tbb::task_arena of exactly the requested count, even above the core
// count (the determinism tests oversubscribe on purpose). TBB caps its workers at its default
// concurrency unless a process-wide tbb::global_control allows more; that control is made only
// when more threads than that are asked for, so a call at or below the core count (every call of
// the CLI's default) changes no process-wide state and two calls at once do not meet.
#pragma once

#include <optional>

#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

namespace so {

class ThreadArena {
  public:
    explicit ThreadArena(int threads) : arena_(threads) {
        if (threads > tbb::info::default_concurrency())
            oversubscribed_.emplace(tbb::global_control::max_allowed_parallelism, size_t(threads));
    }
    tbb::task_arena& arena() { return arena_; }

  private:
    // Before the arena, so that the arena's workers may number `threads` from its first use.
    std::optional<tbb::global_control> oversubscribed_;
    tbb::task_arena arena_;
};

}  // namespace so
