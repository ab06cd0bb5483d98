#include "oracle/oracle_stats.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "core/error.h"
#include "oracle/oracle_stats_json.h"

namespace so {

using nlohmann::json;
using namespace oracle_stats_json;

double OracleLightStats::seconds() const {
    if (area) return area->seconds;
    return hard ? hard->seconds : 0.0;
}

double OracleVerifyStats::seconds() const {
    double s = buildSeconds;
    for (const LightVerification& l : lights) s += l.seconds;
    return s;
}

double OracleStats::shadowRaysPerSecond() const {
    return shadowSeconds > 0 ? double(shadowRays) / shadowSeconds : 0.0;
}

// ---- writing ---------------------------------------------------------------------------------

namespace {

// The texts that are the same in every run: written, never read.
constexpr const char* kUniformNote =
    "a uniform run reaching the same worst-pixel half-width (estimated from each pixel's "
    "variance)";
constexpr const char* kOffsetNote =
    "the shadow ray starts this far from the surface along the normal: an occluder that comes "
    "closer to the ray than that, at the surface or anywhere along it, may be missed; rays to a "
    "light stop a margin of 256 ulp of the light's coordinates short of it";
constexpr const char* kVerifyMethod =
    "independent re-trace in double precision (own BVH, no Embree) from the primary ray on; area "
    "lights by independent uniform samples of the light";
constexpr const char* kToleranceNote =
    "a hard-light pixel is ambiguous where the reference ray passes closer than abs + "
    "per_unit_distance * t + |oracle origin - hit point| to changing its answer";

json finiteOrNull(double v) {
    return std::isfinite(v) ? json(v) : json(nullptr);
}

// The member of `j` at a dotted key ("rays_skipped.background"), made where missing.
json& atKey(json& j, const char* key) {
    json* node = &j;
    for (const char* part = key;;) {
        const char* dot = std::strchr(part, '.');
        if (!dot) return (*node)[part];
        node = &(*node)[std::string(part, dot)];
        part = dot + 1;
    }
}

// Every counter of the table with a key that `keep` accepts (stat_fields.h).
template <class S, class Keep>
void writeFields(json& j, const S& s, Keep keep) {
    for (const StatField<S>& f : S::fields()) {
        if (!f.key || !keep(f.key)) continue;
        std::visit(
            [&](auto m) {
                if constexpr (std::is_same_v<decltype(s.*m), const std::optional<uint64_t>&>) {
                    if (s.*m) atKey(j, f.key) = *(s.*m);
                } else {
                    atKey(j, f.key) = s.*m;
                }
            },
            f.member);
    }
}
template <class S>
void writeFields(json& j, const S& s) {
    writeFields(j, s, [](const char*) { return true; });
}

json hardJson(const HardShadowStats& s) {
    json j;
    writeFields(j, s);
    j["rays_per_second"] = s.raysPerSecond();
    return j;
}

// The samples and mean stated half-width had every pixel stopped after at most `packets`; the
// seconds pro rata of the samples.
json costCurveJson(const AreaShadowStats& s) {
    json curve = json::array();
    for (const CostPoint& p : s.costCurve)
        curve.push_back(
            {{"packets", p.rounds},
             {"samples", p.samples},
             {"mean_half_width", p.meanHalfWidth},
             {"penumbra_mean_half_width",
              p.penumbraMeanHalfWidth ? json(*p.penumbraMeanHalfWidth) : json(nullptr)},
             {"seconds", s.samples ? s.seconds * double(p.samples) / double(s.samples) : 0.0}});
    return curve;
}

json exactPenumbraJson(const ExactPenumbraStats& e) {
    const bool both = e.method == PenumbraMethod::Both;
    json j;
    writeFields(j, e, [&](const char* key) { return keepsExactKey(e, key); });
    json histogram = json::array();
    for (uint64_t c : e.occluders) histogram.push_back(c);
    const auto mean = [&](double total) {
        return e.pixelsExact ? json(total / double(e.pixelsExact)) : json(nullptr);
    };
    j["method"] = penumbraMethodName(e.method);
    j["pixels"] = e.allPixels ? "all" : "penumbra";
    j["not_applied"] = e.notApplied.empty() ? json(nullptr) : json(e.notApplied);
    j["error_kind"] = e.errorKind;
    if (e.errorKind == "bound") {
        j["bound"]["target_half_width"] = e.bound.targetHalfWidth;
        j["bound"]["min_sides"] = e.bound.minSides;
        j["bound"]["max_sides"] = e.bound.maxSides;
        j["bound"]["half_width_mean"] = mean(e.boundHalfWidthSum);
    }
    j["occluders"]["mean"] = mean(double(e.occludersTotal));
    j["occluders"]["p99_at_most"] = occluderQuantileBound(e.occluders, 0.99);
    j["occluders"]["histogram_log2"] = histogram;
    if (both) {
        j["disagreement"]["share_outside_interval"] =
            e.pixelsExact ? json(double(e.outsideInterval) / double(e.pixelsExact)) : json(nullptr);
        j["disagreement"]["mean_abs"] = mean(e.sumAbsDifference);
    }
    return j;
}

json areaJson(const AreaShadowStats& s) {
    json j;
    writeFields(j, s);
    j["sampling"] = s.sampling;
    j["samples_without_ray"] = s.samplesWithoutRay();
    j["spp_mean"] = s.sppMean();
    j["target_error"] = s.targetError ? json(*s.targetError) : json(nullptr);
    j["agreement_target"] = s.agreementTarget ? json(*s.agreementTarget) : json(nullptr);
    j["max_spp"] = s.maxSpp;
    j["share_reached_target"] = s.shareReachedTarget();
    j["uniform_equivalent"]["samples"] = s.uniformSamples();
    j["uniform_equivalent"]["rays"] = s.uniformRays();
    j["uniform_equivalent"]["note"] = kUniformNote;
    j["sampling_efficiency"] = s.samplingEfficiency;
    j["cost_curve"] = costCurveJson(s);
    j["exact_penumbra"] = s.exact ? exactPenumbraJson(*s.exact) : json(nullptr);
    j["rays_per_second"] = s.raysPerSecond();
    return j;
}

json choiceJson(const PenumbraChoice& c) {
    return {{"chosen", penumbraMethodName(c.chosen)},
            {"reason", c.reason},
            {"probe",
             {{"points", c.probePoints},
              {"rays", c.probeRays},
              {"candidates", c.probeCandidates},
              {"occluders", c.probeOccluders},
              {"kept_sampled", c.probeKeptSampled},
              {"bound_sides", c.probeBoundSides}}},
            {"estimate_seconds", {{"exact", c.exactSeconds}, {"sampled", c.sampledSeconds}}}};
}

json lightJson(const OracleLightStats& l) {
    json j = {{"name", l.name}, {"type", lightTypeName(l.type)}, {"method", l.method}};
    if (l.choice) j["penumbra_choice"] = choiceJson(*l.choice);
    if (l.area) {
        j.update(areaJson(*l.area));
        if (l.hard) j["contact_rays"] = hardJson(*l.hard);
    } else if (l.hard) {
        j.update(hardJson(*l.hard));
    }
    return j;
}

json disagreementJson(const VerifyDisagreement& d) {
    json j = {{"x", d.x},
              {"y", d.y},
              {"kind", d.kind},
              {"near_horizon", d.nearHorizon},
              {"cos", d.cosine},
              {"oracle_V", d.oracleV},
              {"reference_V", d.referenceV}};
    if (d.kind == "area") {
        j["oracle_half_width"] = d.oracleHalfWidth;
        j["reference_half_width"] = d.referenceHalfWidth;
    } else {
        j["margin"] = finiteOrNull(d.wsMargin);
        j["reference_occluder_distance"] = finiteOrNull(d.wsOccluderDist);
    }
    return j;
}

json lightVerificationJson(const LightVerification& l) {
    json pixels = json::array();
    for (const VerifyDisagreement& d : l.disagreements) pixels.push_back(disagreementJson(d));
    json j = {{"name", l.light},
              {"test", l.sampled ? kAreaTest : kHardTest},
              {"pixels_checked", l.checked},
              {"random", l.random},
              {"near_horizon", l.nearHorizon},
              {"agree", l.agree},
              {"ambiguous", l.ambiguous},
              {"primary_differs_within_tolerance", l.primaryDiffers},
              {"ambiguous_alpha", l.alphaAmbiguous},
              {"disagreements", l.disagree},
              {"pixels", pixels},
              {"seconds", l.seconds}};
    if (l.sampled) j["z"] = l.zThreshold;
    return j;
}

json verifyJson(const OracleVerifyStats& v) {
    json lights = json::array();
    for (const LightVerification& l : v.lights) lights.push_back(lightVerificationJson(l));
    return {{"method", kVerifyMethod},
            {"pixels_per_light", v.options.pixels},
            {"horizon_deg", v.options.horizonDeg},
            {"area_samples", v.options.areaSamples},
            {"family_alpha", v.options.familyAlpha},
            {"tolerance",
             {{"abs", v.wsToleranceAbs},
              {"per_unit_distance", v.tolerancePerUnitDistance},
              {"note", kToleranceNote}}},
            {"disagreements", v.disagreements()},
            {"seconds", v.seconds()},
            {"build_bvh_seconds", v.buildSeconds},
            {"lights", lights}};
}

}  // namespace

json toJson(const OracleStats& s) {
    json phases = {{"build_bvh", s.buildBvhSeconds},
                   {"primary", s.primarySeconds},
                   {"shadow", s.shadowSeconds}};
    if (s.verify) phases["verify"] = s.verify->seconds();
    json lights = json::array();
    for (const OracleLightStats& l : s.lights) lights.push_back(lightJson(l));
    const glm::dvec3& c = s.frame.wsCenter;
    json j = {
        {"image", {{"width", s.width}, {"height", s.height}}},
        {"threads", s.threads},
        {"phases_seconds", phases},
        {"shadow_rays", s.shadowRays},
        {"closest_hit_queries", s.closestHitQueries},
        {"alpha_tests", {{"primary", s.primaryAlphaTests}, {"shadow", s.shadowAlphaTests}}},
        {"effects", s.effects},
        {"seed", s.seed},
        {"shadow_rays_per_second", s.shadowRaysPerSecond()},
        {"lights", lights},
        {"frame", {{"ws_center", {c.x, c.y, c.z}}, {"scale_exponent", s.frame.scaleExponent}}},
        {"offset_policy",
         {{"method", s.offsetPolicy.method},
          {"skips_origin_triangle", s.offsetPolicy.skipsOriginTriangle},
          {"max_blind_distance", s.offsetPolicy.maxBlindDistance},
          {"max_blind_distance_relative", s.offsetPolicy.maxBlindDistanceRelative},
          {"note", kOffsetNote}}},
        {"embree",
         {{"version", s.embree.version},
          {"scene_flags", s.embree.sceneFlags},
          {"build_quality", s.embree.buildQuality}}},
        {"tbb", {{"version", s.tbbVersion}}},
    };
    if (s.verify) j["verify"] = verifyJson(*s.verify);
    return j;
}

}  // namespace so
