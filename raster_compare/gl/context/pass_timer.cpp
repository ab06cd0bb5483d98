#include "raster_compare/gl/context/pass_timer.h"

#include <algorithm>

namespace so {

void PassTimer::begin(const std::string& pass) {
    frame_.push_back({pass, makeQuery(GL_TIME_ELAPSED)});
    glBeginQuery(GL_TIME_ELAPSED, frame_.back().query.get());
}

void PassTimer::end() {
    // A deferring implementation (llvmpipe bins draws and rasterises them at the next flush)
    // would otherwise charge a pass's work to whichever later query happens to contain the flush:
    // measured, shadow volumes' stencil pass read 0.03 ms and their fill showed up nowhere. On a
    // GPU a flush only submits what is queued.
    glFlush();
    glEndQuery(GL_TIME_ELAPSED);
}

void PassTimer::endFrame(bool keep) {
    // A pass that ran several times in the frame (accumulate's per-sample passes) is their sum.
    std::map<std::string, double> frameMs;
    for (Query& q : frame_) {
        GLuint64 ns = 0;
        glGetQueryObjectui64v(q.query.get(), GL_QUERY_RESULT, &ns);
        frameMs[q.pass] += double(ns) * 1e-6;
    }
    if (keep)
        for (const auto& [pass, ms] : frameMs) msByPass_[pass].push_back(ms);
    frame_.clear();
}

TimingStats PassTimer::stats(const std::string& pass) const {
    const auto it = msByPass_.find(pass);
    return it == msByPass_.end() ? TimingStats{} : timingStats(it->second);
}

}  // namespace so
