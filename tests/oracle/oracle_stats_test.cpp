// The oracle's typed statistics (oracle_stats.h): what toJson writes reads back to the same JSON,
// a broken file is an InputError; and the oracle cache (oracle_cache.h) round trip.
#include <unistd.h>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/channels.h"
#include "core/error.h"
#include "core/lights/light_kind.h"
#include "core/lights/make_light.h"
#include "oracle/oracle.h"
#include "oracle/oracle_cache.h"
#include "oracle/oracle_stats.h"
#include "test_scenes.h"

namespace so::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The square-occluder scene (point, spot, directional) plus three area lights: a rect and a disk
// (one-sided) and a sphere.
Scene lightsOfEveryKind(int width, int height, std::vector<std::string> effects) {
    Scene scene = makeSquareOccluderScene(width, height).scene;
    // cross(u, v) points down
    scene.lights.push_back(rectLight("panel", {0.5, 5.0, 0.25}, {1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}));
    scene.lights.push_back(diskLight("lamp", {2.0, 4.5, 1.0}, {0.0, -1.0, 0.0}, 0.5));
    scene.lights.push_back(sphereLight("globe", {-2.0, 4.0, -1.0}, 0.5));
    scene.effects = std::move(effects);
    finalizeScene(scene);
    return scene;
}

OracleOptions quiet() {
    OracleOptions o;
    o.threads = 2;
    return o;
}

// toJson -> oracleStatsFromJson -> toJson is the identity, in memory and through the text.
void expectRoundTrip(const OracleStats& s) {
    const json j = toJson(s);
    EXPECT_EQ(toJson(oracleStatsFromJson(j, "memory")), j);
    const json parsed = json::parse(j.dump(2));
    EXPECT_EQ(toJson(oracleStatsFromJson(parsed, "text")), j);
    EXPECT_EQ(toJson(oracleStatsFromJson(parsed, "text")).dump(2), j.dump(2));
}

// The fields the typed stats must keep as they were in oracle.json.
void expectShape(const OracleStats& s, const json& j) {
    EXPECT_TRUE(j["threads"].is_number_integer());
    EXPECT_TRUE(j["shadow_rays"].is_number_integer());
    EXPECT_TRUE(j["closest_hit_queries"].is_number_integer());
    EXPECT_TRUE(j["seed"].is_number_integer());
    EXPECT_TRUE(j["frame"]["scale_exponent"].is_number_integer());
    EXPECT_EQ(j["phases_seconds"].contains("verify"), s.verified());
    EXPECT_EQ(j.contains("verify"), s.verified());
    ASSERT_EQ(j["lights"].size(), s.lights.size());
    for (size_t i = 0; i < s.lights.size(); ++i) {
        const json& l = j["lights"][i];
        EXPECT_EQ(l["seconds"].get<double>(), s.lights[i].seconds()) << i;
        EXPECT_TRUE(l["rays_traced"].is_number_integer()) << i;
        EXPECT_EQ(l["name"], s.lights[i].name);
        EXPECT_EQ(l["type"], lightTypeName(s.lights[i].type));
        EXPECT_EQ(l.contains("contact_rays"), s.lights[i].sampled() && s.lights[i].hard);
        if (s.lights[i].sampled()) {
            EXPECT_TRUE(l["max_spp"].is_number_integer());
            EXPECT_TRUE(l["spp_max"].is_number_integer());
            EXPECT_EQ(l["target_error"].is_null(), !s.lights[i].area->targetError);
        }
    }
}

TEST(OracleStats, SampledLightsWithContactRoundTrip) {
    const Scene scene = lightsOfEveryKind(48, 36, {"penumbra", "contact"});
    OracleOptions o = quiet();
    o.area.fixedSpp = 16;
    const OracleResult r = runOracle(scene, o);
    const OracleStats& s = r.stats;
    ASSERT_EQ(s.lights.size(), 6u);
    // point, spot, sun: hard; the area lights sampled, with their contact rays.
    for (size_t i = 0; i < 6; ++i) {
        EXPECT_EQ(s.lights[i].sampled(), i >= 3) << i;
        EXPECT_TRUE(s.lights[i].hard) << i;
    }
    EXPECT_TRUE(s.lights[1].hard->skippedOutsideCone);  // the spot
    EXPECT_FALSE(s.lights[0].hard->skippedOutsideCone);
    EXPECT_EQ(s.lights[3].seconds(), s.lights[3].area->seconds);
    EXPECT_EQ(s.lights[0].seconds(), s.lights[0].hard->seconds);
    EXPECT_FALSE(s.lights[3].area->targetError);  // fixed spp
    for (size_t i = 3; i < 6; ++i) {
        EXPECT_GT(s.lights[i].area->raysTraced, 0u) << i;
        EXPECT_GT(s.lights[i].hard->closestHitQueries, 0u) << i;
    }
    EXPECT_GT(s.lights[1].hard->raysOccluded, 0u);
    EXPECT_FALSE(s.verified());
    EXPECT_EQ(s.disagreements(), 0u);
    const json j = toJson(s);
    EXPECT_TRUE(j["lights"][3]["target_error"].is_null());
    EXPECT_EQ(j["lights"][3]["max_spp"], 16);
    expectShape(s, j);
    expectRoundTrip(s);
}

TEST(OracleStats, HardAreaLightsAndVerifyRoundTrip) {
    const Scene scene = lightsOfEveryKind(40, 30, {"hard"});
    OracleOptions o = quiet();
    o.verify.pixels = 20;
    const OracleResult r = runOracle(scene, o);
    OracleStats s = r.stats;
    ASSERT_TRUE(s.verified());
    ASSERT_EQ(s.verify->lights.size(), scene.lights.size());
    for (const LightVerification& l : s.verify->lights) EXPECT_GT(l.checked, 0u) << l.light;
    // Rect and disk are one-sided: traced at the centre, the rays behind them skipped.
    EXPECT_TRUE(s.lights[3].hard->skippedBehindLight);
    EXPECT_TRUE(s.lights[4].hard->skippedBehindLight);
    EXPECT_FALSE(s.lights[5].hard->skippedBehindLight);
    EXPECT_NE(s.lights[3].method.find("centre"), std::string::npos);
    const json j = toJson(s);
    EXPECT_EQ(j["phases_seconds"]["verify"].get<double>(), s.verify->seconds());
    EXPECT_EQ(j["verify"]["seconds"].get<double>(), s.verify->seconds());
    expectShape(s, j);
    expectRoundTrip(s);

    // Disagreements of both kinds, with the non-finite values that are written as null.
    constexpr double kInf = std::numeric_limits<double>::infinity();
    VerifyDisagreement hard;
    hard.x = 3, hard.y = 4, hard.kind = "shadow", hard.oracleV = 1.0;
    hard.wsMargin = kInf, hard.wsOccluderDist = kInf;
    VerifyDisagreement area;
    area.x = 5, area.y = 6, area.kind = "area", area.nearHorizon = true, area.oracleV = 0.25;
    area.referenceV = 0.5, area.oracleHalfWidth = 0.01, area.referenceHalfWidth = 0.02;
    s.verify->lights[0].disagreements = {hard, area};
    s.verify->lights[0].disagree = 2;
    s.verify->lights[3].sampled = true;
    s.verify->lights[3].zThreshold = 3.5;
    EXPECT_EQ(s.disagreements(), 2u);
    const json k = toJson(s);
    EXPECT_EQ(k["verify"]["disagreements"], 2);
    EXPECT_TRUE(k["verify"]["lights"][0]["pixels"][0]["margin"].is_null());
    EXPECT_FALSE(k["verify"]["lights"][0]["pixels"][1].contains("margin"));
    EXPECT_EQ(k["verify"]["lights"][3]["z"], 3.5);
    expectRoundTrip(s);
}

TEST(OracleStats, AdaptiveSamplingRoundTrip) {
    const Scene scene = lightsOfEveryKind(32, 24, {"hard", "penumbra"});
    OracleOptions o = quiet();
    o.area.targetError = 0.05;
    o.verify.pixels = 8;
    o.verify.areaSamples = 256;
    const OracleResult r = runOracle(scene, o);
    ASSERT_TRUE(r.stats.lights[3].area);
    EXPECT_FALSE(r.stats.lights[3].hard);  // no contact rays without "contact"
    EXPECT_EQ(r.stats.lights[3].area->targetError, 0.05);
    const json j = toJson(r.stats);
    EXPECT_EQ(j["lights"][3]["target_error"], 0.05);
    expectShape(r.stats, j);
    expectRoundTrip(r.stats);
}

// The InputError's field for `j` read back, or "" when it reads.
std::string errorField(const json& j) {
    try {
        oracleStatsFromJson(j, "oracle.json");
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), "oracle.json");
        return e.field();
    }
    return "";
}

TEST(OracleStats, MalformedJsonIsAnInputError) {
    const Scene scene = lightsOfEveryKind(24, 18, {"penumbra", "contact"});
    OracleOptions o = quiet();
    o.area.fixedSpp = 4;
    o.verify.pixels = 4;
    o.verify.areaSamples = 64;
    const json good = toJson(runOracle(scene, o).stats);
    EXPECT_EQ(errorField(good), "");

    json j = good;
    j.erase("shadow_rays");
    EXPECT_EQ(errorField(j), "shadow_rays");
    j = good;
    j["lights"][1]["rays_skipped"].erase("background");
    EXPECT_EQ(errorField(j), "lights[1].rays_skipped.background");
    j = good;
    j["lights"][3]["contact_rays"].erase("seconds");
    EXPECT_EQ(errorField(j), "lights[3].contact_rays.seconds");
    j = good;
    j["verify"]["lights"][0].erase("agree");
    EXPECT_EQ(errorField(j), "verify.lights[0].agree");
    j = good;
    j["threads"] = "2";
    EXPECT_EQ(errorField(j), "threads");
    j = good;
    j["shadow_rays"] = -1;
    EXPECT_EQ(errorField(j), "shadow_rays");
    j = good;
    j["lights"][0]["type"] = "laser";
    EXPECT_EQ(errorField(j), "lights[0].type");
    j = good;
    j["frame"]["ws_center"] = {1.0, 2.0};
    EXPECT_EQ(errorField(j), "frame.ws_center");
    j = good;
    j["lights"] = json::object();
    EXPECT_EQ(errorField(j), "lights");
    EXPECT_EQ(errorField(json::array()), "(top level)");
}

// A fresh folder under the temp directory, removed at the end.
struct TempDir {
    TempDir() {
        path = fs::temp_directory_path() /
               ("so_oracle_cache_test_" + std::to_string(::getpid()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(path);
        fs::create_directories(path);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
    fs::path path;
};

void expectSameImage(const ChannelImage& a, const ChannelImage& b) {
    ASSERT_EQ(a.width(), b.width());
    ASSERT_EQ(a.height(), b.height());
    // The EXR stores the channels sorted by name: compare them by name.
    const std::set<std::string> na(a.names().begin(), a.names().end()),
        nb(b.names().begin(), b.names().end());
    ASSERT_EQ(na, nb);
    for (const std::string& n : na)
        EXPECT_EQ(0, std::memcmp(a.channel(n), b.channel(n), a.pixelCount() * sizeof(float))) << n;
}

Scene cacheScene() {
    return lightsOfEveryKind(32, 24, {"penumbra", "contact"});
}

OracleOptions cacheOptions() {
    OracleOptions o = quiet();
    o.area.fixedSpp = 8;
    o.verify.pixels = 4;
    o.verify.areaSamples = 64;
    return o;
}

// Gives field i of the table the value (i + 1) * scale: every counter distinct.
template <class S>
S numbered(double scale) {
    S s;
    size_t i = 0;
    for (const StatField<S>& f : S::fields()) {
        const double v = double(++i) * scale;
        std::visit(
            [&](auto m) {
                using T = std::remove_cvref_t<decltype(s.*m)>;
                if constexpr (std::is_same_v<T, double>)
                    s.*m = v + 0.25;
                else
                    s.*m = uint64_t(v);
            },
            f.member);
    }
    return s;
}

// Every counter of a table, whatever it is: its value after combineStats(a, b) is the sum (or the
// larger) of a's and b's, and it comes back from oracle.json as it went in.
template <class S>
void expectCombinedAndRoundTripped(const S& a, const S& b, const S& total, const S& back) {
    for (const StatField<S>& f : S::fields()) {
        const std::string key = f.key ? f.key : "(no key)";
        std::visit(
            [&](auto m) {
                using T = std::remove_cvref_t<decltype(a.*m)>;
                if constexpr (std::is_same_v<T, std::optional<uint64_t>>) {
                    const uint64_t x = *(a.*m), y = *(b.*m);
                    EXPECT_EQ(*(total.*m), f.combine == Combine::Sum ? x + y : std::max(x, y))
                        << key;
                } else {
                    EXPECT_EQ(total.*m,
                              f.combine == Combine::Sum ? a.*m + b.*m : std::max(a.*m, b.*m))
                        << key;
                }
                EXPECT_EQ(back.*m, total.*m) << key;
            },
            f.member);
    }
}

TEST(StatFields, EveryCounterIsCombinedWrittenAndRead) {
    OracleStats stats;
    stats.lights.resize(2);
    stats.lights[0].name = "spot";
    stats.lights[0].type = findLightKind("spot")->type();
    const auto hardA = numbered<HardShadowStats>(1.0), hardB = numbered<HardShadowStats>(10.0);
    combineStats(stats.lights[0].hard.emplace(hardA), hardB);
    stats.lights[1].name = "panel";
    stats.lights[1].type = findLightKind("rect")->type();
    auto areaA = numbered<AreaShadowStats>(1.0), areaB = numbered<AreaShadowStats>(10.0);
    // What the reader checks: a share of pixels reached the target, samples cover the rays and
    // the agreeing samples.
    areaA.pixelsReachedTarget = 1, areaB.pixelsReachedTarget = 2;
    areaA.samples = 1000, areaB.samples = 10000;
    combineStats(stats.lights[1].area.emplace(areaA), areaB);
    stats.lights[1].area->exact.emplace(numbered<ExactPenumbraStats>(1.0));
    stats.lights[1].area->exact->method = PenumbraMethod::Both;  // writes every counter
    stats.lights[1].area->exact->errorKind = "bound";            // and the bound's
    const json j = toJson(stats);
    const OracleStats back = oracleStatsFromJson(json::parse(j.dump()), "memory");
    ASSERT_TRUE(back.lights[0].hard && back.lights[1].area && back.lights[1].area->exact);
    expectCombinedAndRoundTripped(hardA, hardB, *stats.lights[0].hard, *back.lights[0].hard);
    expectCombinedAndRoundTripped(areaA, areaB, *stats.lights[1].area, *back.lights[1].area);
    const ExactPenumbraStats& e = *stats.lights[1].area->exact;
    expectCombinedAndRoundTripped(ExactPenumbraStats{}, e, e, *back.lights[1].area->exact);
}

TEST(OracleCache, SecondRunComesFromTheCache) {
    TempDir tmp;
    const Scene scene = cacheScene();
    const OracleOptions o = cacheOptions();
    const CachedOracle first = traceOrLoad(scene, o, {tmp.path, true});
    EXPECT_FALSE(first.fromCache);
    EXPECT_EQ(first.key, oracleCacheKey(scene, o));
    EXPECT_EQ(first.key.size(), 32u);
    EXPECT_TRUE(fs::exists(tmp.path / first.key / "oracle.exr"));
    EXPECT_TRUE(fs::exists(tmp.path / first.key / "oracle.json"));
    // oracle.json is the stats, nothing else.
    std::ifstream in(tmp.path / first.key / "oracle.json");
    EXPECT_EQ(json::parse(in), toJson(first.stats));

    const CachedOracle second = traceOrLoad(scene, o, {tmp.path, true});
    EXPECT_TRUE(second.fromCache);
    EXPECT_EQ(second.key, first.key);
    expectSameImage(first.image, second.image);
    EXPECT_EQ(toJson(second.stats).dump(2), toJson(first.stats).dump(2));

    // Another option, another entry.
    OracleOptions other = o;
    other.area.seed = 7;
    EXPECT_NE(oracleCacheKey(scene, other), first.key);
    EXPECT_FALSE(traceOrLoad(scene, other, {tmp.path, true}).fromCache);
    // Nothing left behind under a temporary name.
    size_t entries = 0;
    for (const auto& e : fs::directory_iterator(tmp.path)) {
        EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
        ++entries;
    }
    EXPECT_EQ(entries, 2u);
}

TEST(OracleCache, CorruptEntryIsTracedAgain) {
    TempDir tmp;
    const Scene scene = cacheScene();
    const OracleOptions o = cacheOptions();
    const CachedOracle first = traceOrLoad(scene, o, {tmp.path, true});
    const fs::path json = tmp.path / first.key / "oracle.json";
    const fs::path exr = tmp.path / first.key / "oracle.exr";

    EXPECT_TRUE(first.warnings.empty());
    std::ofstream(json) << "{ \"image\": ";  // not JSON
    CachedOracle again = traceOrLoad(scene, o, {tmp.path, true});
    EXPECT_FALSE(again.fromCache);
    expectSameImage(first.image, again.image);
    // The warning is the caller's to print (the library writes nothing to stderr).
    ASSERT_EQ(again.warnings.size(), 1u);
    EXPECT_EQ(again.warnings[0].rfind("oracle cache entry ", 0), 0u) << again.warnings[0];
    EXPECT_NE(again.warnings[0].find("invalid JSON): tracing again"), std::string::npos)
        << again.warnings[0];
    EXPECT_TRUE(traceOrLoad(scene, o, {tmp.path, true}).fromCache);  // stored again

    nlohmann::json j = toJson(first.stats);
    j.erase("lights");  // JSON, but not the stats
    std::ofstream(json) << j.dump(2);
    EXPECT_FALSE(traceOrLoad(scene, o, {tmp.path, true}).fromCache);

    std::ofstream(exr) << "not an EXR";
    again = traceOrLoad(scene, o, {tmp.path, true});
    EXPECT_FALSE(again.fromCache);
    expectSameImage(first.image, again.image);
    EXPECT_TRUE(traceOrLoad(scene, o, {tmp.path, true}).fromCache);
}

TEST(OracleCache, UseFalseTracesAndStoresNothing) {
    TempDir tmp;
    const Scene scene = cacheScene();
    const OracleOptions o = cacheOptions();
    const fs::path dir = tmp.path / "cache";
    const CachedOracle r = traceOrLoad(scene, o, {dir, false});
    EXPECT_FALSE(r.fromCache);
    EXPECT_FALSE(fs::exists(dir));
    EXPECT_EQ(r.image.width(), 32);
    EXPECT_TRUE(r.stats.verified());
}

}  // namespace
}  // namespace so::test
