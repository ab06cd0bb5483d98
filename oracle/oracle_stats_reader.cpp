// oracle.json read back (oracleStatsFromJson, oracle_stats.h): what trace-merge joins the bands'
// stats from, through the one reader of user JSON (core/json_reader.h): this file is written by
// toJson, where a non-finite number is null (read as NaN, JsonReader::nullableNumber) and counters
// are 64-bit unsigned (JsonReader::count), and its errors name the dotted path from the file's top
// ("lights[0].area.").
#include "oracle/oracle_stats.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>

#include "core/error.h"
#include "core/json_reader.h"
#include "core/lights/light_kind.h"
#include "oracle/oracle_stats_json.h"

namespace so {

using nlohmann::json;
using namespace oracle_stats_json;

// ---- reading ---------------------------------------------------------------------------------

namespace {

// One object of oracle.json and its dotted path from the file's top, read through the one reader
// of user JSON (core/json_reader.h), so its errors read like every other file's.
class Fields {
  public:
    Fields(const json& j, const JsonReader& r, std::string path)
        : j_(j), r_(r), path_(std::move(path)) {
        r_.requireObject(j_, path_.empty() ? "(top level)" : path_);
    }

    bool has(const char* key) const { return j_.contains(key); }
    bool isNull(const char* key) const { return at(key).is_null(); }
    std::vector<double> numbers(const char* key) const { return r_.numbers(at(key), name(key)); }
    Fields object(const char* key) const { return Fields(at(key), r_, name(key)); }
    // The elements of an array, each checked to be an object.
    std::vector<Fields> objects(const char* key) const {
        const json& a = at(key);
        r_.requireArray(a, name(key));
        std::vector<Fields> out;
        for (size_t i = 0; i < a.size(); ++i)
            out.emplace_back(a[i], r_, JsonReader::index(name(key), i));
        return out;
    }
    std::string str(const char* key) const { return r_.string(at(key), name(key)); }
    std::vector<std::string> strings(const char* key) const {
        return r_.strings(at(key), name(key));
    }
    std::string oneOf(const char* key, const std::string& what,
                      const std::vector<std::string>& names) const {
        return r_.oneOf(at(key), name(key), what, names);
    }
    bool boolean(const char* key) const { return r_.boolean(at(key), name(key)); }
    uint64_t u64(const char* key) const { return r_.count(at(key), name(key)); }
    uint32_t u32(const char* key) const {
        const uint64_t v = u64(key);
        if (v > std::numeric_limits<uint32_t>::max())
            fail(name(key), "must be in [0, " +
                                std::to_string(std::numeric_limits<uint32_t>::max()) + "], got " +
                                std::to_string(v));
        return uint32_t(v);
    }
    int i32(const char* key) const {
        return r_.integer(at(key), name(key), std::numeric_limits<int>::min(),
                          std::numeric_limits<int>::max());
    }
    // A number; null (how nlohmann writes a non-finite number) reads as NaN.
    double number(const char* key) const { return r_.nullableNumber(at(key), name(key)); }
    std::optional<double> optionalNumber(const char* key) const {
        if (at(key).is_null()) return std::nullopt;
        return number(key);
    }
    glm::dvec3 vec3(const char* key) const { return r_.vec3(at(key), name(key)); }
    [[noreturn]] void fail(const std::string& field, const std::string& message) const {
        r_.fail(field, message);
    }
    std::string name(const char* key) const { return JsonReader::join(path_, key); }

  private:
    const json& at(const char* key) const { return r_.at(j_, path_, key); }
    const json& j_;
    const JsonReader& r_;
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
    e.allPixels = f.oneOf("pixels", "pixel set", {"all", "penumbra"}) == "all";
    if (!f.isNull("not_applied")) e.notApplied = f.str("not_applied");
    e.errorKind = f.oneOf("error_kind", "error kind", {"exact", "bound"});
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
    f.fail(f.name("type"),
           "unknown light type \"" + printable(name, 40) + "\" (valid: " + lightKindNames() + ")");
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
    const std::string test = f.oneOf("test", "test", {kAreaTest, kHardTest});
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
    const JsonReader reader(file);
    const Fields f(j, reader, "");
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

}  // namespace so
