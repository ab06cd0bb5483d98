// Shadow rays from the raster path's own G-buffer (issue 53, the `raytraced` family): what RT cores
// do on a GPU, traced by Embree on the CPU. From each pixel's point of the camera pass (the
// positions and normals it rasterized, so the pixels a GPU would shade), `spp` rays a frame to
// points on the light: an Owen-scrambled Sobol sequence per pixel (core/sobol.h; the pixel's own
// scramble seed, which is a Cranley-Patterson-like decorrelation between pixels), indexed by
// frameIndex * spp + s, so that the frames of a sequence continue one low-discrepancy sequence
// per pixel. Each pixel depends on nothing but its inputs and the frame index: the result is
// bit-identical at any thread count.
//
// The estimate per pixel is the oracle's ratio (docs/oracle.md, "Area lights"): V = sum(v G) /
// sum(G), G = cos(receiver) cos(emitter) / r^2 (one-sided for rect, disk and polygon lights),
// samples uniform by area (raster_compare/gl/lights/). Point, spot and directional lights: every
// ray goes to the light's one point (direction), V = 0 where the surface faces away (and outside
// a spot's cone), as the oracle's hard shadow. Where a ray goes on the light its kind says
// (raster_light_kind.h, pointSeenFrom: a sphere's visible cap). Alpha-tested meshes cut their
// masks' holes: the BVH is built by the Embree library the oracle's is (embree/triangle_scene.h,
// whose filter evaluates core/alpha_mask.h at each candidate hit), never through the oracle.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/local_frame.h"
#include "core/scene.h"

namespace so {

// One frame's G-buffer as the camera pass holds it: RGBA32F per pixel, in GL's row order (bottom
// row first), local-frame positions (w 1 where a surface was hit) and camera-facing normals.
struct ShadowRayGBuffer {
    int width = 0, height = 0;
    const float* lsPosition = nullptr;
    const float* lsNormal = nullptr;
};

struct ShadowRaySettings {
    int spp = 1;
    int frameIndex = 0;
    bool hitDistance = false;  // trace closest hits (slower) for the mean blocker distance
    int threads = 0;           // 0: the hardware's
    // Per pixel, in the G-buffer's order, how many of the `spp` rays to trace (0 to spp): an
    // adaptive denoiser's counts (denoisers/rtg.cpp). Null: spp everywhere. Pixel p's ray s uses
    // the sequence's index frameIndex * spp + s either way, so a pixel given n rays traces the
    // first n of the rays it would trace at the full count.
    const std::vector<uint8_t>* samplesPerPixel = nullptr;
};

struct ShadowRayFrame {
    // Per pixel, in the G-buffer's order: RG, the V estimate and the mean distance (local units)
    // from the point to the blockers its occluded rays hit (0 where none was hit or not asked).
    std::vector<float> visibilityAndHit;
    uint64_t raysTraced = 0;  // every ray traced (up to spp per pixel that sees the light's side)
    uint64_t pixelsTraced = 0;
};

class ShadowRayTracer {
  public:
    // Builds the BVH of `scene`'s meshes in `frame` (the raster path's local frame), for any light.
    // `scene` must outlive it (the alpha masks' filters read its meshes).
    ShadowRayTracer(const Scene& scene, const LocalFrame& frame);
    ~ShadowRayTracer();
    ShadowRayTracer(const ShadowRayTracer&) = delete;
    ShadowRayTracer& operator=(const ShadowRayTracer&) = delete;

    ShadowRayFrame trace(const ShadowRayGBuffer& gbuffer, const Light& light,
                         const ShadowRaySettings& settings) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace so
