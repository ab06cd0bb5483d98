#include "oracle/oracle_stats.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "core/error.h"
#include "core/lights/light_kind.h"

namespace so {

using nlohmann::json;

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
constexpr const char* kAreaTest =
    "area: |V - V_ref| <= z * combined stderr (+ bound where NAME.bound bounds V)";
constexpr const char* kHardTest = "hard: exact re-trace, V must match";

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

bool isDisagreementKey(const char* key) {
    return std::strncmp(key, "disagreement.", 13) == 0;
}

bool isBoundKey(const char* key) {
    return std::strncmp(key, "bound.", 6) == 0;
}

// The exact pass's counters a light's JSON holds: disagreement with both, bound for bounded lights.
bool keepsExactKey(const ExactPenumbraStats& e, const char* key) {
    if (isDisagreementKey(key)) return e.method == PenumbraMethod::Both;
    if (isBoundKey(key)) return e.errorKind == "bound";
    return true;
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

// ---- reading ---------------------------------------------------------------------------------

namespace {

// Typed access to one JSON object; every failure is an InputError naming the field's full path.
class Fields {
  public:
    Fields(const json& j, const std::string& file, std::string path)
        : j_(j), file_(file), path_(std::move(path)) {
        if (!j_.is_object()) fail(path_.empty() ? "(top level)" : path_, "must be an object");
    }

    bool has(const char* key) const { return j_.contains(key); }
    bool isNull(const char* key) const { return at(key).is_null(); }
    // An array of numbers.
    std::vector<double> numbers(const char* key) const {
        const json& v = at(key);
        if (!v.is_array()) fail(name(key), "must be an array of numbers");
        std::vector<double> out;
        for (const json& e : v) {
            if (!e.is_number()) fail(name(key), "must be an array of numbers");
            out.push_back(e.get<double>());
        }
        return out;
    }
    Fields object(const char* key) const { return Fields(at(key), file_, name(key)); }
    // The elements of an array, each checked to be an object.
    std::vector<Fields> objects(const char* key) const {
        const json& a = at(key);
        if (!a.is_array()) fail(name(key), "must be an array");
        std::vector<Fields> out;
        for (size_t i = 0; i < a.size(); ++i)
            out.emplace_back(a[i], file_, name(key) + "[" + std::to_string(i) + "]");
        return out;
    }
    std::string str(const char* key) const {
        const json& v = at(key);
        if (!v.is_string()) fail(name(key), "must be a string");
        return v.get<std::string>();
    }
    std::vector<std::string> strings(const char* key) const {
        const json& v = at(key);
        if (!v.is_array()) fail(name(key), "must be an array of strings");
        std::vector<std::string> out;
        for (const json& e : v) {
            if (!e.is_string()) fail(name(key), "must be an array of strings");
            out.push_back(e.get<std::string>());
        }
        return out;
    }
    bool boolean(const char* key) const {
        const json& v = at(key);
        if (!v.is_boolean()) fail(name(key), "must be true or false");
        return v.get<bool>();
    }
    uint64_t u64(const char* key) const {
        const json& v = at(key);
        if (v.is_number_unsigned()) return v.get<uint64_t>();
        if (v.is_number_integer() && v.get<int64_t>() >= 0) return uint64_t(v.get<int64_t>());
        fail(name(key), "must be a non-negative integer");
    }
    uint32_t u32(const char* key) const {
        const uint64_t v = u64(key);
        if (v > std::numeric_limits<uint32_t>::max()) fail(name(key), "out of range");
        return uint32_t(v);
    }
    int i32(const char* key) const {
        const json& v = at(key);
        if (!v.is_number_integer()) fail(name(key), "must be an integer");
        if (v.is_number_unsigned() ? v.get<uint64_t>() > uint64_t(std::numeric_limits<int>::max())
                                   : (v.get<int64_t>() < std::numeric_limits<int>::min() ||
                                      v.get<int64_t>() > std::numeric_limits<int>::max()))
            fail(name(key), "out of range");
        return int(v.get<int64_t>());
    }
    // A number; null (how nlohmann writes a non-finite number) reads as NaN.
    double number(const char* key) const {
        const json& v = at(key);
        if (v.is_null()) return std::numeric_limits<double>::quiet_NaN();
        if (!v.is_number()) fail(name(key), "must be a number");
        return v.get<double>();
    }
    std::optional<double> optionalNumber(const char* key) const {
        if (at(key).is_null()) return std::nullopt;
        return number(key);
    }
    glm::dvec3 vec3(const char* key) const {
        const json& v = at(key);
        if (!v.is_array() || v.size() != 3) fail(name(key), "must be an array of 3 numbers");
        glm::dvec3 out;
        for (int k = 0; k < 3; ++k) {
            if (!v[k].is_number()) fail(name(key), "must be an array of 3 numbers");
            out[k] = v[k].get<double>();
        }
        return out;
    }
    [[noreturn]] void fail(const std::string& field, const std::string& message) const {
        throwInputError(file_, field, message);
    }
    std::string name(const char* key) const { return path_.empty() ? key : path_ + "." + key; }

  private:
    const json& at(const char* key) const {
        const auto it = j_.find(key);
        if (it == j_.end()) fail(name(key), "missing");
        return *it;
    }
    const json& j_;
    const std::string& file_;
    std::string path_;
};

// Every counter of the table with a key that `keep` accepts, from `f` (its dotted keys nest).
template <class S, class Keep>
void readFields(const Fields& f, S& s, Keep keep) {
    for (const StatField<S>& field : S::fields()) {
        if (!field.key || !keep(field.key)) continue;
        std::optional<Fields> parent;  // the object holding the leaf, when nested
        const char* leaf = field.key;
        for (const char* dot; (dot = std::strchr(leaf, '.'));) {
            const std::string part(leaf, dot);
            parent.emplace((parent ? *parent : f).object(part.c_str()));
            leaf = dot + 1;
        }
        const Fields& in = parent ? *parent : f;
        std::visit(
            [&](auto m) {
                using T = std::remove_cvref_t<decltype(s.*m)>;
                if constexpr (std::is_same_v<T, std::optional<uint64_t>>) {
                    if (in.has(leaf)) s.*m = in.u64(leaf);
                } else if constexpr (std::is_same_v<T, uint64_t>) {
                    s.*m = in.u64(leaf);
                } else {
                    s.*m = in.number(leaf);
                }
            },
            field.member);
    }
}
template <class S>
void readFields(const Fields& f, S& s) {
    readFields(f, s, [](const char*) { return true; });
}

HardShadowStats readHard(const Fields& f) {
    HardShadowStats s;
    readFields(f, s);
    return s;
}

ExactPenumbraStats readExactPenumbra(const Fields& f) {
    ExactPenumbraStats e;
    e.method = parsePenumbraMethod(f.str("method"), "oracle.json", f.name("method"));
    if (e.method == PenumbraMethod::Sampled || e.method == PenumbraMethod::Auto)
        f.fail(f.name("method"), "must be exact or both");
    const std::string pixels = f.str("pixels");
    if (pixels != "all" && pixels != "penumbra")
        f.fail(f.name("pixels"), "must be all or penumbra");
    e.allPixels = pixels == "all";
    if (!f.isNull("not_applied")) e.notApplied = f.str("not_applied");
    e.errorKind = f.str("error_kind");
    if (e.errorKind != "exact" && e.errorKind != "bound")
        f.fail(f.name("error_kind"), "must be exact or bound");
    if (e.errorKind == "bound") {
        const Fields b = f.object("bound");
        e.bound.targetHalfWidth = b.number("target_half_width");
        e.bound.minSides = uint32_t(b.u64("min_sides"));
        e.bound.maxSides = uint32_t(b.u64("max_sides"));
    }
    readFields(f, e, [&](const char* key) { return keepsExactKey(e, key); });
    const Fields occ = f.object("occluders");
    const std::vector<double> histogram = occ.numbers("histogram_log2");
    if (histogram.size() != e.occluders.size())
        occ.fail(occ.name("histogram_log2"),
                 "must hold " + std::to_string(e.occluders.size()) + " counts");
    for (size_t k = 0; k < histogram.size(); ++k) {
        if (!(histogram[k] >= 0) || histogram[k] != std::floor(histogram[k]))
            occ.fail(occ.name("histogram_log2"), "must hold non-negative integers");
        e.occluders[k] = uint64_t(histogram[k]);
    }
    return e;
}

AreaShadowStats readArea(const Fields& f) {
    AreaShadowStats s;
    readFields(f, s);
    s.sampling = f.str("sampling");
    if (s.samples < s.raysTraced) f.fail(f.name("samples"), "fewer than rays_traced");
    if (s.samplesAgreeing > s.samples) f.fail(f.name("samples_agreeing"), "more than samples");
    s.targetError = f.optionalNumber("target_error");
    s.agreementTarget = f.optionalNumber("agreement_target");
    s.maxSpp = f.i32("max_spp");
    // The share times the pixels gives back the count exactly (it was count / pixels).
    const double share = f.number("share_reached_target");
    if (!(share >= 0.0 && share <= 1.0)) f.fail(f.name("share_reached_target"), "not in [0, 1]");
    s.pixelsReachedTarget = uint64_t(std::llround(share * double(s.pixelsSampled)));
    s.samplingEfficiency = f.number("sampling_efficiency");
    for (const Fields& p : f.objects("cost_curve"))
        s.costCurve.push_back({p.i32("packets"), p.u64("samples"), p.number("mean_half_width"),
                               p.optionalNumber("penumbra_mean_half_width")});
    if (f.has("exact_penumbra") && !f.isNull("exact_penumbra"))
        s.exact = readExactPenumbra(f.object("exact_penumbra"));
    return s;
}

LightType readLightType(const Fields& f) {
    const std::string name = f.str("type");
    if (const LightKind* kind = findLightKind(name)) return kind->type();
    f.fail(f.name("type"), "unknown light type \"" + printable(name, 40) + "\"");
}

PenumbraChoice readChoice(const Fields& f) {
    PenumbraChoice c;
    c.chosen = parsePenumbraMethod(f.str("chosen"), "oracle.json", f.name("chosen"));
    if (c.chosen != PenumbraMethod::Exact && c.chosen != PenumbraMethod::Sampled)
        f.fail(f.name("chosen"), "must be exact or sampled");
    c.reason = f.str("reason");
    const Fields probe = f.object("probe");
    c.probePoints = probe.u64("points");
    c.probeRays = probe.u64("rays");
    c.probeCandidates = probe.u64("candidates");
    c.probeOccluders = probe.u64("occluders");
    c.probeKeptSampled = probe.u64("kept_sampled");
    c.probeBoundSides = probe.u64("bound_sides");
    const Fields estimate = f.object("estimate_seconds");
    c.exactSeconds = estimate.number("exact");
    c.sampledSeconds = estimate.number("sampled");
    return c;
}

// A sampled light is told by its "sampling" field; its hard pass (contact rays) is nested.
OracleLightStats readLight(const Fields& f) {
    OracleLightStats l;
    l.name = f.str("name");
    l.type = readLightType(f);
    l.method = f.str("method");
    if (f.has("penumbra_choice")) l.choice = readChoice(f.object("penumbra_choice"));
    if (f.has("sampling")) {
        l.area = readArea(f);
        if (f.has("contact_rays")) l.hard = readHard(f.object("contact_rays"));
    } else {
        l.hard = readHard(f);
    }
    return l;
}

VerifyDisagreement readDisagreement(const Fields& f) {
    VerifyDisagreement d;
    d.x = f.i32("x");
    d.y = f.i32("y");
    d.kind = f.str("kind");
    d.nearHorizon = f.boolean("near_horizon");
    d.cosine = f.number("cos");
    d.oracleV = f.number("oracle_V");
    d.referenceV = f.number("reference_V");
    if (d.kind == "area") {
        d.oracleHalfWidth = f.number("oracle_half_width");
        d.referenceHalfWidth = f.number("reference_half_width");
    } else {  // null: no occluder (or no margin), written for any non-finite value
        constexpr double kInf = std::numeric_limits<double>::infinity();
        d.wsMargin = f.optionalNumber("margin").value_or(kInf);
        d.wsOccluderDist = f.optionalNumber("reference_occluder_distance").value_or(kInf);
    }
    return d;
}

LightVerification readLightVerification(const Fields& f) {
    LightVerification l;
    l.light = f.str("name");
    const std::string test = f.str("test");
    if (test != kAreaTest && test != kHardTest)
        f.fail(f.name("test"), "unknown test \"" + printable(test, 60) + "\"");
    l.sampled = test == kAreaTest;
    l.checked = f.u64("pixels_checked");
    l.random = f.u64("random");
    l.nearHorizon = f.u64("near_horizon");
    l.agree = f.u64("agree");
    l.ambiguous = f.u64("ambiguous");
    l.primaryDiffers = f.u64("primary_differs_within_tolerance");
    l.alphaAmbiguous = f.u64("ambiguous_alpha");
    l.disagree = f.u64("disagreements");
    for (const Fields& p : f.objects("pixels")) l.disagreements.push_back(readDisagreement(p));
    l.seconds = f.number("seconds");
    if (l.sampled) l.zThreshold = f.number("z");
    return l;
}

OracleVerifyStats readVerify(const Fields& f) {
    OracleVerifyStats v;
    v.options.pixels = f.i32("pixels_per_light");
    v.options.horizonDeg = f.number("horizon_deg");
    v.options.areaSamples = f.i32("area_samples");
    v.options.familyAlpha = f.number("family_alpha");
    const Fields tolerance = f.object("tolerance");
    v.wsToleranceAbs = tolerance.number("abs");
    v.tolerancePerUnitDistance = tolerance.number("per_unit_distance");
    v.buildSeconds = f.number("build_bvh_seconds");
    for (const Fields& l : f.objects("lights")) v.lights.push_back(readLightVerification(l));
    return v;
}

}  // namespace

OracleStats oracleStatsFromJson(const json& j, const std::string& file) {
    const Fields f(j, file, "");
    OracleStats s;
    const Fields image = f.object("image");
    s.width = image.i32("width");
    s.height = image.i32("height");
    s.threads = f.i32("threads");
    const Fields phases = f.object("phases_seconds");
    s.buildBvhSeconds = phases.number("build_bvh");
    s.primarySeconds = phases.number("primary");
    s.shadowSeconds = phases.number("shadow");
    s.shadowRays = f.u64("shadow_rays");
    s.closestHitQueries = f.u64("closest_hit_queries");
    const Fields alpha = f.object("alpha_tests");
    s.primaryAlphaTests = alpha.u64("primary");
    s.shadowAlphaTests = alpha.u64("shadow");
    s.effects = f.strings("effects");
    s.seed = f.u32("seed");
    for (const Fields& l : f.objects("lights")) s.lights.push_back(readLight(l));
    const Fields frame = f.object("frame");
    s.frame.wsCenter = frame.vec3("ws_center");
    s.frame.scaleExponent = frame.i32("scale_exponent");
    const Fields offset = f.object("offset_policy");
    s.offsetPolicy.method = offset.str("method");
    s.offsetPolicy.skipsOriginTriangle = offset.boolean("skips_origin_triangle");
    s.offsetPolicy.maxBlindDistance = offset.number("max_blind_distance");
    s.offsetPolicy.maxBlindDistanceRelative = offset.number("max_blind_distance_relative");
    const Fields embree = f.object("embree");
    s.embree.version = embree.str("version");
    s.embree.sceneFlags = embree.str("scene_flags");
    s.embree.buildQuality = embree.str("build_quality");
    // The trace command's oracle.json keeps the TBB version under libraries.
    s.tbbVersion = f.has("tbb") || !f.has("libraries") ? f.object("tbb").str("version")
                                                       : f.object("libraries").str("tbb");
    if (f.has("verify")) s.verify = readVerify(f.object("verify"));
    return s;
}

// ---- merging the bands of trace --tile ---------------------------------------------------------

namespace {

// A band's curve at `rounds` packets: its own point there, or, past its last point (every one of
// its pixels had stopped), that last point. Null without a curve.
const CostPoint* curveAt(const AreaShadowStats& s, int rounds) {
    for (const CostPoint& p : s.costCurve)
        if (p.rounds == rounds) return &p;
    if (!s.costCurve.empty() && s.costCurve.back().rounds < rounds) return &s.costCurve.back();
    return nullptr;
}

// The whole image's cost curve: read at the rounds of the band that sampled longest (the whole
// run reads at the same ones), each band's mean weighted by its pixels.
std::vector<CostPoint> mergeCurves(const std::vector<const AreaShadowStats*>& bands,
                                   const std::vector<uint64_t>& penumbraPixels,
                                   uint64_t pixelsSampled) {
    const AreaShadowStats* longest = nullptr;
    for (const AreaShadowStats* b : bands)
        if (!b->costCurve.empty() &&
            (!longest || b->costCurve.back().rounds > longest->costCurve.back().rounds))
            longest = b;
    std::vector<CostPoint> curve;
    if (!longest) return curve;
    uint64_t penumbraTotal = 0;
    for (uint64_t n : penumbraPixels) penumbraTotal += n;
    for (const CostPoint& at : longest->costCurve) {
        CostPoint point{at.rounds, 0, 0.0, std::nullopt};
        double penumbraSum = 0.0;
        for (size_t b = 0; b < bands.size(); ++b) {
            const CostPoint* p = curveAt(*bands[b], at.rounds);
            if (!p) continue;
            point.samples += p->samples;
            point.meanHalfWidth += p->meanHalfWidth * double(bands[b]->pixelsSampled);
            if (p->penumbraMeanHalfWidth)
                penumbraSum += *p->penumbraMeanHalfWidth * double(penumbraPixels[b]);
        }
        point.meanHalfWidth /= double(pixelsSampled);
        if (penumbraTotal) point.penumbraMeanHalfWidth = penumbraSum / double(penumbraTotal);
        curve.push_back(point);
    }
    return curve;
}

// The bands' exact passes: the counts add up; the sum of |V_exact - V| too (the bands' pixels
// are disjoint), so the merged means are the whole run's.
// The bands' exact passes: the counts add up; the sum of |V_exact - V| too (the bands' pixels
// are disjoint), so the merged means are the whole run's.
ExactPenumbraStats mergeExact(const std::vector<const AreaShadowStats*>& bands) {
    ExactPenumbraStats total;
    total.method = bands.front()->exact->method;
    total.allPixels = bands.front()->exact->allPixels;
    total.notApplied = bands.front()->exact->notApplied;
    total.errorKind = bands.front()->exact->errorKind;
    total.bound = bands.front()->exact->bound;
    for (const AreaShadowStats* b : bands) {
        const ExactPenumbraStats& e = *b->exact;
        combineStats(total, e);
        for (size_t k = 0; k < total.occluders.size(); ++k) total.occluders[k] += e.occluders[k];
    }
    return total;
}

AreaShadowStats mergeArea(const std::vector<const AreaShadowStats*>& bands,
                          const std::vector<uint64_t>& penumbraPixels) {
    const AreaShadowStats& first = *bands.front();
    AreaShadowStats total;
    total.sampling = first.sampling;
    total.targetError = first.targetError;
    total.agreementTarget = first.agreementTarget;
    total.maxSpp = first.maxSpp;
    double efficiency = 0.0;
    for (const AreaShadowStats* b : bands) {
        combineStats(total, *b);
        efficiency += b->samplingEfficiency * double(b->pixelsSampled);
    }
    if (total.pixelsSampled) {
        total.samplingEfficiency = efficiency / double(total.pixelsSampled);
        total.costCurve = mergeCurves(bands, penumbraPixels, total.pixelsSampled);
    }
    if (std::all_of(bands.begin(), bands.end(),
                    [](const AreaShadowStats* b) { return b->exact.has_value(); }))
        total.exact = mergeExact(bands);
    return total;
}

OracleLightStats mergeLight(const std::vector<TileStats>& tiles, size_t li) {
    const OracleLightStats& first = tiles.front().stats.lights[li];
    OracleLightStats l;
    l.name = first.name;
    l.type = first.type;
    l.method = first.method;
    // Every band probed the same coarse image of the whole view: the same choice; each estimated
    // its own points' seconds, which add up.
    l.choice = first.choice;
    if (l.choice) {
        l.choice->exactSeconds = l.choice->sampledSeconds = 0.0;
        for (const TileStats& t : tiles)
            if (const auto& c = t.stats.lights[li].choice) {
                l.choice->exactSeconds += c->exactSeconds;
                l.choice->sampledSeconds += c->sampledSeconds;
            }
    }
    std::vector<const AreaShadowStats*> areas;
    std::vector<uint64_t> penumbra;
    for (const TileStats& t : tiles) {
        const OracleLightStats& b = t.stats.lights[li];
        if (b.name != first.name || b.area.has_value() != first.area.has_value() ||
            b.hard.has_value() != first.hard.has_value())
            throw std::invalid_argument("mergeTileStats: light " + std::to_string(li) +
                                        " differs between bands (\"" + printable(first.name) +
                                        "\", \"" + printable(b.name) + "\")");
        if (b.area) {
            areas.push_back(&*b.area);
            penumbra.push_back(li < t.penumbraPixels.size() ? t.penumbraPixels[li] : 0);
        }
        if (b.hard) combineStats(l.hard ? *l.hard : l.hard.emplace(), *b.hard);
    }
    if (!areas.empty()) l.area = mergeArea(areas, penumbra);
    return l;
}

}  // namespace

OracleStats mergeTileStats(const std::vector<TileStats>& tiles, int width, int height) {
    if (tiles.empty()) throw std::invalid_argument("mergeTileStats: no bands");
    const OracleStats& first = tiles.front().stats;
    OracleStats s;
    s.width = width;
    s.height = height;
    s.threads = first.threads;
    s.effects = first.effects;
    s.seed = first.seed;
    s.frame = first.frame;
    s.offsetPolicy = first.offsetPolicy;
    s.embree = first.embree;
    s.tbbVersion = first.tbbVersion;
    for (const TileStats& t : tiles) {
        const OracleStats& b = t.stats;
        if (b.lights.size() != first.lights.size())
            throw std::invalid_argument("mergeTileStats: the bands have different light counts (" +
                                        std::to_string(first.lights.size()) + ", " +
                                        std::to_string(b.lights.size()) + ")");
        s.buildBvhSeconds += b.buildBvhSeconds;
        s.primarySeconds += b.primarySeconds;
        s.shadowSeconds += b.shadowSeconds;
        s.shadowRays += b.shadowRays;
        s.closestHitQueries += b.closestHitQueries;
        s.primaryAlphaTests += b.primaryAlphaTests;
        s.shadowAlphaTests += b.shadowAlphaTests;
        s.offsetPolicy.maxBlindDistance =
            std::max(s.offsetPolicy.maxBlindDistance, b.offsetPolicy.maxBlindDistance);
        s.offsetPolicy.maxBlindDistanceRelative = std::max(s.offsetPolicy.maxBlindDistanceRelative,
                                                           b.offsetPolicy.maxBlindDistanceRelative);
    }
    for (size_t li = 0; li < first.lights.size(); ++li) s.lights.push_back(mergeLight(tiles, li));
    return s;
}

}  // namespace so
