// `--penumbra auto` (docs/oracle.md, "Exact penumbrae"): per area light, the exact pass where its
// cost estimate is below sampling to the requested target, sampling otherwise. The estimate comes
// from a cheap probe: both passes run on a sparse set of the image's points (a coarse image of the
// same view, one pixel in 64, or one G-buffer point in 64), and their work is counted, not timed,
// so the choice is the same at any thread count, on any machine, and in every band of a tiled
// trace (the coarse image is the whole view's). Counts become seconds through constants measured
// with bench_exact_penumbra (docs/benchmarks.md); they decide which pass runs, never what either
// pass answers.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "oracle/accel.h"
#include "oracle/area_light.h"
#include "oracle/area_shadow.h"
#include "oracle/exact_penumbra.h"
#include "oracle/exact_scene.h"
#include "oracle/surface_buffer.h"

namespace so {

// The probe's points: a surface buffer and the slots of it that the probe uses (null: every
// slot the camera hit).
struct PenumbraProbe {
    const SurfaceBuffer* sb = nullptr;
    const std::vector<uint8_t>* slots = nullptr;
    const MeshFacing* facing = nullptr;  // as the exact pass takes it
    // The scene's triangles: a shadow ray's cost grows with the log of them (the BVH's depth).
    uint64_t sceneTriangles = 0;
};

// Exact wins unless its estimate exceeds sampling's by more than this factor: the two fits'
// errors compound in the ratio (up to 2.6 times on the bunny), so nearer estimates do not tell
// the two apart, and between two methods of about the same cost the one without sampling error is
// the better answer. On the calibration's lights it picks the measured cheaper method, or exact
// where that cost at most 1.26 times sampling (chess_board's lamp panel).
inline constexpr double kPenumbraExactMargin = 1.5;
// Exact where its estimate is at most kPenumbraExactMargin times sampling's (ties included).
PenumbraMethod cheaperPenumbraMethod(double exactSeconds, double sampledSeconds);

// The slots of `sb` one in `every` of its points (by slot), for a probe of the buffer itself.
std::vector<uint8_t> sparseSlots(const SurfaceBuffer& sb, size_t every);

// The choice for `light`, whose V the sampled pass would estimate with `sampling` (stream: the
// light's index) and the exact pass would compute with `options`; imagePoints: the points the
// camera hit in the image (or band) being traced. `notApplied`: why the exact pass does not apply
// to the light ("" where it does): then sampling, without a probe. Runs inside the caller's arena.
PenumbraChoice choosePenumbraMethod(const Accel& accel, const ExactScene* exact,
                                    const PenumbraProbe& probe, const AreaLight& light,
                                    uint32_t stream, const AreaSampling& sampling,
                                    const ExactPenumbraOptions& options, uint64_t imagePoints,
                                    const std::string& notApplied);

}  // namespace so
