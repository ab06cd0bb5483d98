// The oracle checks itself (`trace --verify N`, docs/oracle.md#verification): pixels chosen at
// random with the seed, plus pixels whose light sits near the receiver's horizon, are traced again
// by an independent exact tracer in double precision (exact_tracer.h: its own BVH, no Embree),
// from the primary ray on.
//
//   hard lights (and area lights without "penumbra"): the reference's V is 0 or 1; any difference
//     is a disagreement unless the reference ray passes within the tolerance of changing its answer
//     (an edge, a surface it starts on, the attached-shadow or cone boundary, an alpha test within
//     its margins: exact_alpha.h): then "ambiguous".
//   sampled area lights: the reference estimates V from independent uniform samples of the light
//     (its own sampler and random numbers); a disagreement is |V - V_ref| above z times the
//     combined standard error, z Bonferroni-corrected over the pixels checked (family-wise false
//     alarm rate 1%); where the oracle's V is bounded (disk and sphere lights with --penumbra
//     exact: NAME.bound), |V - V_ref| above the bound's half-width plus z times the reference's
//     standard error. Such a pixel is also checked against the polygons' bound (disk_bounds.h, an
//     independent method: inscribed and circumscribed polygons where the exact pass integrates
//     the circle's arcs) at the oracle's own point: V +- NAME.bound must meet that interval.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/local_frame.h"
#include "core/scene.h"
#include "oracle/exact_scene.h"
#include "oracle/surface_buffer.h"

namespace so {

struct VerifyOptions {
    int pixels = 0;  // random pixels per light; 0: no verification
    double horizonDeg =
        3.0;  // plus pixels whose light is this close to the horizon (up to `pixels`)
    int areaSamples = 4096;     // reference samples per area-light pixel
    double familyAlpha = 0.01;  // area lights: chance of any false alarm over a light's pixels
    // The degrees of freedom of the oracle's stated sampled intervals (area_shadow.h):
    // kAdaptiveDof for adaptive runs, kReplicas - 1 for a fixed count. Set by the oracle.
    int oracleDof = 4;
};

// One pixel where the reference disagrees with the oracle.
struct VerifyDisagreement {
    int x = 0, y = 0;
    std::string kind;  // "shadow", "primary", "area"
    bool nearHorizon = false;
    double cosine = 0.0;  // towards the light (centre), at the reference's hit point
    double oracleV = 0.0, referenceV = 0.0;
    // area: 95% half-widths (a bounded pixel's: its bound's, the interval being sure)
    double oracleHalfWidth = 0.0, referenceHalfWidth = 0.0;
    double wsMargin = 0.0;        // hard: how far the reference ray is from changing its answer
    double wsOccluderDist = 0.0;  // hard: the reference's first occluder (inf: none)
};

struct LightVerification {
    std::string light;
    bool sampled = false;  // an area light with "penumbra"
    uint64_t checked = 0, random = 0, nearHorizon = 0;
    uint64_t agree = 0, ambiguous = 0, disagree = 0;
    uint64_t primaryDiffers = 0;  // a different triangle seen, within the tolerance (ambiguous)
    // Of the ambiguous pixels, those where an alpha test was within its margins (exact_alpha.h):
    // the float path's texel or alpha rounding could decide it either way.
    uint64_t alphaAmbiguous = 0;
    // area: the Bonferroni-corrected two-sided normal quantile (a bounded pixel's threshold);
    // a sampled pixel's is the Student-t quantile for the same tail (Welch's degrees of freedom)
    double zThreshold = 0.0;
    std::vector<VerifyDisagreement> disagreements;  // all of them
    double seconds = 0.0;
};

class Verifier {
  public:
    enum class Verdict { Agree, Ambiguous, Disagree };

    // Builds the reference BVH from the scene's double-precision vertices in `frame`. camera null:
    // points mode (trace --points, oracle/points.h): there is no primary ray to re-trace, so the
    // reference takes the oracle's triangle and barycentrics, rebuilds the point on its own double
    // vertices and checks the shadow rays from there.
    Verifier(const Scene& scene, const LocalFrame& frame, const Camera* camera,
             const VerifyOptions& options, uint32_t seed);

    // V, stderr_ (nullable for hard lights), spp (nullable), bound (nullable: NAME.bound, the
    // half-widths of bounded pixels, 0 elsewhere) and exact (nullable: NAME.exact, 1 where the
    // exact pass gave V; with bound, those pixels are checked against the polygons' bound too)
    // are the oracle's channels.
    LightVerification verifyLight(const Light& light, uint32_t lightIndex, bool sampled,
                                  const SurfaceBuffer& sb, const float* V, const float* stderr_,
                                  const float* spp, const float* bound = nullptr,
                                  const float* exact = nullptr) const;
    const ExactTracer& tracer() const { return exact_.tracer(); }

    // The tolerance of the hard-light test, in local units (where the scene's half-extent is in
    // [0.5, 1)): kTolAbs + kTolPerT * t, plus the distance between the oracle's hit point and the
    // reference's (two traces of the same primary ray). This is the oracle's promise: an occluder
    // that the shadow ray clips by more than that is seen. The oracle's own origin offset
    // (offset.h) must stay inside it, so it is not added: an offset that hides occluders is a
    // disagreement, which is how the 256-ulp offset of issue 9 shows.
    static constexpr double kTolAbs = 1.0 / 1048576.0;   // 2^-20: ~1e-6 of the scene's size
    static constexpr double kTolPerT = 1.0 / 2097152.0;  // 2^-21: of a float direction, per unit

  private:
    struct PixelRef;
    std::vector<size_t> choosePixels(const Light& light, uint32_t lightIndex,
                                     const SurfaceBuffer& sb, uint64_t& random,
                                     uint64_t& nearHorizon) const;
    // Agree: the reference sees the oracle's triangle (ref is set); otherwise the pixel stops here.
    // alphaAmbiguous: an alpha test on the way was within its margins (set, never cleared).
    Verdict primary(int x, int y, const SurfaceBuffer& sb, size_t slot, PixelRef& ref,
                    VerifyDisagreement& d, bool& alphaAmbiguous) const;
    Verdict hardPixel(const Light& light, const PixelRef& ref, float oracleV, VerifyDisagreement& d,
                      bool& alphaAmbiguous) const;
    Verdict areaPixel(const Light& light, uint32_t lightIndex, size_t pixel, const PixelRef& ref,
                      float oracleV, float oracleStderr, float oracleSpp, float oracleBound,
                      double z, VerifyDisagreement& d) const;
    // A disk or sphere light's exact pixel against the polygons' bound at the exact pass's point.
    Verdict polygonBoundPixel(const Light& light, const SurfaceBuffer& sb, size_t slot,
                              float oracleV, float oracleBound, VerifyDisagreement& d) const;

    ExactScene exact_;
    LocalFrame frame_;
    std::optional<Camera> camera_;  // none in points mode
    VerifyOptions options_;
    uint32_t seed_;
    double oracleQuantile95_;  // the oracle's stated 95% Student-t quantile (options_.oracleDof)
};

uint64_t disagreementCount(const std::vector<LightVerification>& lights);

// Student's t with `dof` (real, > 0) degrees of freedom: P(|T| > t), and the t at which that is
// `alpha` (the verifier's thresholds; exposed for tests).
double studentTwoSidedP(double t, double dof);
double studentQuantileTwoSided(double alpha, double dof);

}  // namespace so
