#include "raster_compare/gl/time/shadow_history.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <utility>

#include <glm/vec4.hpp>

#include "core/camera.h"
#include "core/channels.h"
#include "core/scene_pose.h"

namespace so {
namespace {

// How far, in pixel footprints at the point, a previous frame's texel may lie from the reprojected
// point and still count as the same surface: a slack for the rounding of float positions and of
// the motion, plus, per pixel of image distance between the texel's centre and the reprojected
// point, the footprint stretched by a surface seen obliquely (4: up to about 76 degrees from the
// view direction). Further off, the texel is another surface (disocclusion) and is not read; when
// the pixel the point falls in is another surface, the point was hidden and has no history.
constexpr double kSlackFootprints = 0.5;
constexpr double kObliqueFootprints = 4.0;
// float32 positions round at about 6e-8 of their magnitude, both the stored and the current one.
constexpr double kPositionRounding = 1e-6;

// The geometry channels a frame is matched by: A, P.*, id.mesh.
struct GeometryView {
    const float* hit;
    const float* position[3];
    const float* mesh;

    explicit GeometryView(const ChannelImage& image)
        : hit(image.channel(channels::kHit)),
          position{image.channel(channels::kPX), image.channel(channels::kPY),
                   image.channel(channels::kPZ)},
          mesh(image.channel(channels::kMeshId)) {}
    bool hits(size_t i) const { return hit[i] > 0.5f; }
    glm::dvec3 wsPosition(size_t i) const {
        return {position[0][i], position[1][i], position[2][i]};
    }
};

ChannelImage copyGeometry(const ChannelImage& image) {
    ChannelImage copy(image.width(), image.height());
    for (const char* name :
         {channels::kHit, channels::kPX, channels::kPY, channels::kPZ, channels::kMeshId}) {
        const float* from = image.channel(name);
        std::copy(from, from + image.pixelCount(), copy.addChannel(name));
    }
    return copy;
}

// The world size of one pixel at wsPoint seen by `camera` (its vertical extent at that depth).
double pixelFootprint(const CameraDesc& camera, const glm::dvec3& wsPoint) {
    const glm::dvec3 wsForward = glm::normalize(camera.wsTarget - camera.wsEye);
    const double depth = glm::dot(wsPoint - camera.wsEye, wsForward);
    const double tanHalfVfov = std::tan(0.5 * camera.vfovDeg * std::numbers::pi / 180.0);
    return 2.0 * depth * tanHalfVfov / camera.height;
}

// The [min, max] of the current V over the pixels that hit in the 3x3 neighbourhood of (x, y):
// what the history is clamped to. Background pixels (V 0 by convention) do not widen it.
std::pair<float, float> neighbourhoodRange(const GeometryView& geometry, const float* v, int width,
                                           int height, int x, int y) {
    float lo = v[size_t(y) * size_t(width) + size_t(x)], hi = lo;
    for (int ny = std::max(y - 1, 0); ny <= std::min(y + 1, height - 1); ++ny)
        for (int nx = std::max(x - 1, 0); nx <= std::min(x + 1, width - 1); ++nx) {
            const size_t n = size_t(ny) * size_t(width) + size_t(nx);
            if (!geometry.hits(n)) continue;
            lo = std::min(lo, v[n]);
            hi = std::max(hi, v[n]);
        }
    return {lo, hi};
}

}  // namespace

ShadowHistory::ShadowHistory(HistorySettings settings, std::string light)
    : settings_(settings), light_(std::move(light)) {}

std::optional<float> ShadowHistory::sample(const glm::dvec2& imagePos, long mesh,
                                           const glm::dvec3& wsPrevious) const {
    const int width = geometry_.width(), height = geometry_.height();
    if (!(imagePos.x >= 0.0 && imagePos.x < width && imagePos.y >= 0.0 && imagePos.y < height))
        return std::nullopt;  // off screen in the previous frame
    const GeometryView previous(geometry_);
    const double footprint = pixelFootprint(camera_, wsPrevious);
    const double rounding = kPositionRounding * glm::length(wsPrevious);
    const auto sameSurface = [&](int x, int y) {
        const size_t i = size_t(y) * size_t(width) + size_t(x);
        if (!previous.hits(i) || long(previous.mesh[i]) != mesh) return false;
        const double pixels = std::hypot(x + 0.5 - imagePos.x, y + 0.5 - imagePos.y);
        const double tolerance =
            footprint * (kSlackFootprints + kObliqueFootprints * pixels) + rounding;
        return glm::length(previous.wsPosition(i) - wsPrevious) <= tolerance;
    };
    // The pixel the point falls in decides: it saw the same surface, or the point was hidden.
    if (!sameSurface(int(imagePos.x), int(imagePos.y))) return std::nullopt;
    // The value: bilinear over the 4 texel centres around the point (centres at +0.5), over those
    // that saw the same surface, their weights renormalised.
    const double fx = imagePos.x - 0.5, fy = imagePos.y - 0.5;
    const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
    double sum = 0.0, weightSum = 0.0;
    for (int dy = 0; dy <= 1; ++dy)
        for (int dx = 0; dx <= 1; ++dx) {
            const int x = x0 + dx, y = y0 + dy;
            const double wx = dx ? fx - x0 : 1.0 - (fx - x0);
            const double wy = dy ? fy - y0 : 1.0 - (fy - y0);
            if (x < 0 || x >= width || y < 0 || y >= height || wx * wy <= 0.0) continue;
            if (!sameSurface(x, y)) continue;
            sum += wx * wy * resolved_[size_t(y) * size_t(width) + size_t(x)];
            weightSum += wx * wy;
        }
    // The containing pixel is one of the 4 with a weight of at least 1/4, and it matched.
    return float(sum / weightSum);
}

const glm::dmat4& ShadowHistory::motionToPrevious(const Scene& scene, size_t mesh, double t) {
    if (motions_.size() != scene.meshes.size()) {
        motions_.assign(scene.meshes.size(), glm::dmat4(1.0));
        motionKnown_.assign(scene.meshes.size(), 0);
    }
    if (!motionKnown_[mesh]) {
        motions_[mesh] = meshMotion(scene, mesh, t, t_);
        motionKnown_[mesh] = 1;
    }
    return motions_[mesh];
}

std::vector<float> ShadowHistory::resolve(const Scene& scene, const HistoryFrame& current) {
    const ChannelImage& image = *current.image;
    const float* v = image.channel(channels::lightChannel(light_, channels::kVisibility));
    std::vector<float> out(v, v + image.pixelCount());
    const bool usable = have_ && settings_.weight > 0.0 && geometry_.width() == image.width() &&
                        geometry_.height() == image.height();
    if (usable) {
        motionKnown_.assign(scene.meshes.size(), 0);
        const GeometryView geometry(image);
        const Camera previousCamera(camera_);
        const int width = image.width(), height = image.height();
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const size_t i = size_t(y) * size_t(width) + size_t(x);
                if (!geometry.hits(i)) continue;
                const long mesh = long(geometry.mesh[i]);
                if (mesh < 0 || size_t(mesh) >= scene.meshes.size()) continue;
                const glm::dvec3 wsPrevious =
                    glm::dvec3(motionToPrevious(scene, size_t(mesh), current.t) *
                               glm::dvec4(geometry.wsPosition(i), 1.0));
                const std::optional<glm::dvec2> imagePos = previousCamera.project(wsPrevious);
                if (!imagePos) continue;
                std::optional<float> history = sample(*imagePos, mesh, wsPrevious);
                if (!history) continue;  // disoccluded or off screen: the current V alone
                if (settings_.clamp) {
                    const auto [lo, hi] = neighbourhoodRange(geometry, v, width, height, x, y);
                    history = std::clamp(*history, lo, hi);
                }
                out[i] = float(settings_.weight * double(*history) +
                               (1.0 - settings_.weight) * double(v[i]));
            }
    }
    resolved_ = out;
    geometry_ = copyGeometry(image);
    camera_ = current.camera;
    t_ = current.t;
    have_ = true;
    return out;
}

}  // namespace so
