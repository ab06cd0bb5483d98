#include "raster_compare/compare/temporal.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/camera.h"
#include "core/channels.h"
#include "core/error.h"

namespace so {

namespace ch = channels;

namespace {

bool sameCamera(const CameraDesc& a, const CameraDesc& b) {
    return a.wsEye == b.wsEye && a.wsTarget == b.wsTarget && a.wsUp == b.wsUp &&
           a.vfovDeg == b.vfovDeg && a.width == b.width && a.height == b.height;
}

// One frame's planes for one light.
struct FramePlanes {
    FramePlanes(const TemporalFrame& f, const std::string& light)
        : w(f.oracle->width()), h(f.oracle->height()) {
        if (f.raster->width() != w || f.raster->height() != h)
            throw std::invalid_argument("temporal flicker: a frame's raster image is " +
                                        std::to_string(f.raster->width()) + " x " +
                                        std::to_string(f.raster->height()) + ", its oracle " +
                                        std::to_string(w) + " x " + std::to_string(h));
        const ChannelImage &o = *f.oracle, &r = *f.raster;
        Ao = o.channel(ch::kHit), Ar = r.channel(ch::kHit);
        Px = o.channel(ch::kPX), Py = o.channel(ch::kPY), Pz = o.channel(ch::kPZ);
        mo = o.channel(ch::kMeshId), po = o.channel(ch::kPrimId);
        mr = r.channel(ch::kMeshId), pr = r.channel(ch::kPrimId);
        Vo = o.channel(ch::lightChannel(light, ch::kVisibility));
        Vr = r.channel(ch::lightChannel(light, ch::kVisibility));
        Co = o.channel(ch::lightChannel(light, ch::kCosine));
        const std::string se = ch::lightChannel(light, ch::kStdErr);
        SE = o.has(se) ? o.channel(se) : nullptr;
    }
    // What computeLightMetrics counts: both hit, the same triangle, facing the light.
    bool counted(size_t i) const {
        return Ao[i] != 0.0f && Ar[i] != 0.0f && mo[i] == mr[i] && po[i] == pr[i] && Co[i] > 0.0f;
    }
    int w, h;
    const float *Ao, *Ar, *Px, *Py, *Pz, *mo, *po, *mr, *pr, *Vo, *Vr, *Co;
    const float* SE;  // sampled area lights only
};

// The pixel of `prev` that holds world point wsP, or -1.
long trackedPixel(const Camera& prevCamera, const glm::dvec3& wsP, int w, int h, double radius) {
    const std::optional<glm::dvec2> xy = prevCamera.project(wsP);
    if (!xy) return -1;
    const double fx = std::floor(xy->x), fy = std::floor(xy->y);
    if (!(fx >= 0.0 && fy >= 0.0 && fx < w && fy < h)) return -1;
    if (std::abs(xy->x - fx - 0.5) > radius || std::abs(xy->y - fy - 0.5) > radius) return -1;
    return long(fy) * w + long(fx);
}

// Where the point wsP of mesh `mesh` in the next frame was in the previous one; `moved` says
// whether that differs from wsP (so that a still pixel is matched to itself, without rounding).
glm::dvec3 previousPoint(const MeshMotions* motion, float mesh, const glm::dvec3& wsP,
                         bool& moved) {
    moved = false;
    if (!motion || !(mesh >= 0.0f) || size_t(mesh) >= motion->size()) return wsP;
    const glm::dmat4& prevFromNext = (*motion)[size_t(mesh)];
    if (prevFromNext == glm::dmat4(1.0)) return wsP;
    moved = true;
    return glm::dvec3(prevFromNext * glm::dvec4(wsP, 1.0));
}

}  // namespace

std::optional<double> TemporalFlicker::rate() const {
    if (tracked == 0) return std::nullopt;
    return double(flickering) / double(tracked);
}

size_t TemporalFlicker::worstPair() const {
    if (pairs.empty()) throw std::invalid_argument("TemporalFlicker::worstPair: no pairs");
    size_t worst = 0;
    for (size_t k = 1; k < pairs.size(); ++k)
        if (pairs[k].flickering > pairs[worst].flickering) worst = k;
    return worst;
}

void TemporalFlicker::add(const FramePairFlicker& p) {
    pairs.push_back(p);
    tracked += p.tracked;
    flickering += p.flickering;
}

void TemporalFlicker::addToJson(nlohmann::json& row) const {
    const std::optional<double> r = rate();
    row["temporal_flicker_rate"] = r ? nlohmann::json(*r) : nlohmann::json(nullptr);
    row["temporal_tracked_pairs"] = tracked;
    row["temporal_flickering_pairs"] = flickering;
    row["temporal_frames"] = pairs.size() + 1;
}

FramePairFlicker compareFramePair(const TemporalFrame& prev, const TemporalFrame& next,
                                  const std::string& light, const TemporalOptions& options,
                                  std::vector<uint8_t>* mask, const MeshMotions* motion) {
    const FramePlanes a(prev, light), b(next, light);
    const Camera prevCamera(prev.camera);
    const bool still = sameCamera(prev.camera, next.camera) && a.w == b.w && a.h == b.h;
    FramePairFlicker out;
    if (mask) mask->assign(size_t(b.w) * size_t(b.h), 0);
    for (long i = 0; i < long(b.w) * b.h; ++i) {
        if (!b.counted(size_t(i))) continue;
        bool moved = false;
        const glm::dvec3 wsP =
            previousPoint(motion, b.mo[i], glm::dvec3(b.Px[i], b.Py[i], b.Pz[i]), moved);
        const long j =
            still && !moved ? i : trackedPixel(prevCamera, wsP, a.w, a.h, options.trackRadius);
        if (j < 0 || !a.counted(size_t(j)) || a.mo[j] != b.mo[i] || a.po[j] != b.po[i]) continue;
        ++out.tracked;
        const double dVo = std::abs(double(b.Vo[i]) - double(a.Vo[j]));
        const double dVr = std::abs(double(b.Vr[i]) - double(a.Vr[j]));
        const double tolerance =
            a.SE && b.SE ? options.stderrFactor * std::hypot(double(a.SE[j]), double(b.SE[i])) +
                               options.epsilon
                         : 0.0;
        const bool flickers = dVr > options.rasterJump && dVo <= tolerance;
        out.flickering += flickers;
        if (mask) (*mask)[size_t(i)] = flickers ? 2 : 1;
    }
    return out;
}

TemporalFlicker computeTemporalFlicker(const std::vector<TemporalFrame>& frames,
                                       const std::string& light, const TemporalOptions& options) {
    TemporalFlicker out;
    for (size_t k = 0; k + 1 < frames.size(); ++k)
        out.add(compareFramePair(frames[k], frames[k + 1], light, options));
    return out;
}

}  // namespace so
