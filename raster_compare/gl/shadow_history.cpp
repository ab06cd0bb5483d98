#include "raster_compare/gl/shadow_history.h"

#include <utility>

#include "core/channels.h"

namespace so {

// Interface first (issue 52): the reprojection and blend are filled in with temporal=on.

ShadowHistory::ShadowHistory(HistorySettings settings, std::string light)
    : settings_(settings), light_(std::move(light)) {}

std::vector<float> ShadowHistory::resolve(const Scene&, const HistoryFrame& current) {
    const float* v =
        current.image->channel(channels::lightChannel(light_, channels::kVisibility));
    std::vector<float> out(v, v + current.image->pixelCount());
    resolved_ = out;
    camera_ = current.camera;
    t_ = current.t;
    have_ = true;
    return out;
}

}  // namespace so
