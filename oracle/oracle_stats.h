// What a run of the oracle reports about itself (docs/oracle.md): typed, filled by runOracle, and
// turned into JSON only where oracle.json is written (toJson) or read back (oracleStatsFromJson).
// Each light holds its passes' own statistics (pass_stats.h), whose counters are written, read and
// merged through their field tables. Values that follow from others (rays per second, spp mean,
// the verify totals) are methods, so the JSON cannot disagree with itself.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "core/scene.h"
#include "oracle/pass_stats.h"
#include "oracle/verify.h"

namespace so {

struct OracleLightStats {
    std::string name;
    LightType type{};                      // set from the scene's light, or oracle.json's "type"
    std::string method;                    // how the light was traced, for people
    std::optional<AreaShadowStats> area;   // sampled (penumbra) area lights
    std::optional<PenumbraChoice> choice;  // --penumbra auto, area lights with "penumbra"
    // Every other light; for a sampled area light, its contact rays (with "contact" only).
    std::optional<HardShadowStats> hard;

    bool sampled() const { return area.has_value(); }
    // oracle.json's lights[i].seconds: the sampled pass for sampled lights, else the hard pass.
    double seconds() const;
};

struct OracleFrameStats {
    glm::dvec3 wsCenter{0.0};
    int scaleExponent = 0;
};

struct OracleOffsetStats {
    std::string method;
    bool skipsOriginTriangle = true;
    double maxBlindDistance = 0.0;  // world units
    double maxBlindDistanceRelative = 0.0;
};

struct OracleEmbreeStats {
    std::string version, sceneFlags, buildQuality;
};

// What --verify found (verify.h).
struct OracleVerifyStats {
    VerifyOptions options;
    double wsToleranceAbs = 0.0;            // Verifier::kTolAbs in world units
    double tolerancePerUnitDistance = 0.0;  // Verifier::kTolPerT
    double buildSeconds = 0.0;              // the reference BVH
    std::vector<LightVerification> lights;  // one per light, in scene order

    uint64_t disagreements() const { return disagreementCount(lights); }
    double seconds() const;  // buildSeconds plus every light's
};

struct OracleStats {
    int width = 0, height = 0;
    int threads = 0;
    double buildBvhSeconds = 0.0, primarySeconds = 0.0, shadowSeconds = 0.0;
    uint64_t shadowRays = 0, closestHitQueries = 0;
    uint64_t primaryAlphaTests = 0, shadowAlphaTests = 0;  // alpha tests (core/alpha_mask.h)
    std::vector<std::string> effects;
    uint32_t seed = 0;
    std::vector<OracleLightStats> lights;  // in scene order
    OracleFrameStats frame;
    OracleOffsetStats offsetPolicy;
    OracleEmbreeStats embree;
    std::string tbbVersion;
    std::optional<OracleVerifyStats> verify;  // with --verify only

    double shadowRaysPerSecond() const;
    bool verified() const { return verify.has_value(); }  // --verify ran (whatever it found)
    uint64_t disagreements() const { return verify ? verify->disagreements() : 0; }
};

// Exactly the run-dependent part of oracle.json (docs/oracle.md).
nlohmann::json toJson(const OracleStats& stats);
// The inverse of toJson: toJson(oracleStatsFromJson(toJson(s), f)) == toJson(s). Throws InputError
// naming `file` and the field on a missing or mistyped field. A null where a number is expected
// reads as NaN (nlohmann writes non-finite numbers as null); derived values are not read.
OracleStats oracleStatsFromJson(const nlohmann::json& json, const std::string& file);

}  // namespace so
