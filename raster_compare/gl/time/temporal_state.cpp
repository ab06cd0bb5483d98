#include "raster_compare/gl/time/temporal_state.h"

#include <algorithm>
#include <cmath>

namespace so {

namespace {

// ls' = (ws - c') 2^-e' and ws = ls 2^e + c, as matrices.
glm::dmat4 lsFromWsMatrix(const LocalFrame& f) {
    glm::dmat4 m(std::ldexp(1.0, -f.exponent));
    m[3] = glm::dvec4(-f.wsCenter * std::ldexp(1.0, -f.exponent), 1.0);
    return m;
}
glm::dmat4 wsFromLsMatrix(const LocalFrame& f) {
    glm::dmat4 m(std::ldexp(1.0, f.exponent));
    m[3] = glm::dvec4(f.wsCenter, 1.0);
    return m;
}

}  // namespace

std::vector<float> previousFromLocalPerMesh(const TemporalState* state, size_t meshes,
                                            const LocalFrame& now, const LocalFrame& before) {
    const glm::dmat4 wsFromLs = wsFromLsMatrix(now), prevLsFromWs = lsFromWsMatrix(before);
    std::vector<float> out(16 * std::max<size_t>(meshes, 1), 0.0f);
    for (size_t m = 0; m < std::max<size_t>(meshes, 1); ++m) {
        const glm::dmat4 motion = state ? state->wsPreviousFromWs(m) : glm::dmat4(1.0);
        const glm::dmat4 prevLsFromLs = prevLsFromWs * motion * wsFromLs;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                out[16 * m + 4 * size_t(c) + size_t(r)] = float(prevLsFromLs[c][r]);
    }
    return out;
}

void TemporalState::beginFrame(int frameIndex, std::vector<glm::dmat4> wsPreviousFromWs) {
    std::lock_guard<std::mutex> lock(mutex_);
    frameIndex_ = frameIndex;
    motion_ = std::move(wsPreviousFromWs);
}

glm::dmat4 TemporalState::wsPreviousFromWs(size_t mesh) const {
    return mesh < motion_.size() ? motion_[mesh] : glm::dmat4(1.0);
}

const ResolvedFrame* TemporalState::before(const void* owner, const std::string& light, int width,
                                           int height) const {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto byFrame = frames_.find({owner, light});
    if (byFrame == frames_.end()) return nullptr;
    const auto f = byFrame->second.find(frameIndex_ - 1);
    if (f == byFrame->second.end() || f->second.width != width || f->second.height != height)
        return nullptr;
    return &f->second;
}

void TemporalState::keep(const void* owner, const std::string& light, ResolvedFrame frame) {
    std::lock_guard<std::mutex> lock(mutex_);
    std::map<int, ResolvedFrame>& byFrame = frames_[{owner, light}];
    byFrame.erase(byFrame.begin(), byFrame.lower_bound(frameIndex_ - 1));
    byFrame[frameIndex_] = std::move(frame);
}

RayHistoryStore& TemporalState::rayHistory(const void* owner) {
    std::lock_guard<std::mutex> lock(mutex_);
    return rays_[owner];
}

}  // namespace so
