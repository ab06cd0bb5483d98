#include "raster_compare/gl/pass_timer.h"

#include <algorithm>

namespace so {

void PassTimer::begin(const std::string& pass) {
    frame_.push_back({pass, makeQuery(GL_TIME_ELAPSED)});
    glBeginQuery(GL_TIME_ELAPSED, frame_.back().query.get());
}

void PassTimer::end() {
    glEndQuery(GL_TIME_ELAPSED);
}

void PassTimer::endFrame(bool keep) {
    for (Query& q : frame_) {
        GLuint64 ns = 0;
        glGetQueryObjectui64v(q.query.get(), GL_QUERY_RESULT, &ns);
        if (keep) msByPass_[q.pass].push_back(double(ns) * 1e-6);
    }
    frame_.clear();
}

TimingStats PassTimer::stats(const std::string& pass) const {
    const auto it = msByPass_.find(pass);
    return it == msByPass_.end() ? TimingStats{} : timingStats(it->second);
}

}  // namespace so
