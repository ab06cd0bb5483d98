// The raster path against the oracle (ctest label "gl"; skipped with the reason where no EGL
// display or GL 4.5 context can be had).
#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <cstdlib>
#include <cstring>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "bunny_scene.h"
#include "core/channels.h"
#include "core/error.h"
#include "core/lights/make_light.h"
#include "gl_test_context.h"
#include "raster_compare/compare/gate.h"
#include "raster_compare/compare/metrics.h"
#include "raster_compare/compare/penumbra_width.h"
#include "raster_compare/gl/context/gl_context.h"
#include "raster_compare/gl/render/renderer.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"
#include "raster_compare/gl/technique.h"
#include "raster_compare/gl/volumes/shadow_volume_geometry.h"
#include "test_scenes.h"

namespace so::test {
namespace {

namespace ch = channels;

ChannelImage raster(const Scene& scene, const std::string& technique,
                    const std::vector<std::string>& settings) {
    std::string why;
    RasterOptions o;
    o.frames = 1;
    o.warmup = 0;
    return renderRaster(scene, *createTechnique(technique, settings), o, *glContext(why)).image;
}

// Pixels to compare: both paths see the same triangle and the oracle says the light faces it.
// `boundaryRadius`: also leave out pixels within that many pixels of an oracle shadow boundary.
struct Comparison {
    size_t counted = 0, agree = 0, falseShadow = 0, falseLit = 0, oracleLit = 0, oracleShadow = 0;
    double agreement() const { return counted ? double(agree) / double(counted) : 0.0; }
};

Comparison compare(const ChannelImage& oracle, const ChannelImage& raster, const std::string& light,
                   int boundaryRadius) {
    const int w = oracle.width(), h = oracle.height();
    const float* Vo = oracle.channel(ch::lightChannel(light, ch::kVisibility));
    const float* Co = oracle.channel(ch::lightChannel(light, ch::kCosine));
    const float* Vr = raster.channel(ch::lightChannel(light, ch::kVisibility));
    const float *mo = oracle.channel(ch::kMeshId), *po = oracle.channel(ch::kPrimId);
    const float *mr = raster.channel(ch::kMeshId), *pr = raster.channel(ch::kPrimId);
    const float* Ao = oracle.channel(ch::kHit);
    std::vector<uint8_t> boundary(size_t(w) * size_t(h), 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            if (Ao[i] == 0.0f) continue;
            for (int d = 0; d < 2; ++d) {
                const int xn = x + (d == 0), yn = y + (d == 1);
                if (xn >= w || yn >= h) continue;
                const size_t j = size_t(yn) * size_t(w) + size_t(xn);
                if (Ao[j] != 0.0f && (Vo[i] > 0.5f) != (Vo[j] > 0.5f))
                    boundary[i] = boundary[j] = 1;
            }
        }
    Comparison c;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            if (Ao[i] == 0.0f || Co[i] <= 0.0f || mo[i] != mr[i] || po[i] != pr[i]) continue;
            bool near = false;
            for (int dy = -boundaryRadius; dy <= boundaryRadius && !near; ++dy)
                for (int dx = -boundaryRadius; dx <= boundaryRadius && !near; ++dx) {
                    const int xx = x + dx, yy = y + dy;
                    near = xx >= 0 && yy >= 0 && xx < w && yy < h &&
                           boundary[size_t(yy) * size_t(w) + size_t(xx)];
                }
            if (near) continue;
            ++c.counted;
            const bool lo = Vo[i] > 0.5f, lr = Vr[i] > 0.5f;
            (lo ? c.oracleLit : c.oracleShadow) += 1;
            c.agree += lo == lr;
            c.falseShadow += lo && !lr;
            c.falseLit += !lo && lr;
        }
    return c;
}

// `settings` of the shadow-map family's parameters, kept only where the technique has them.
std::vector<std::string> settingsFor(const TechniqueInfo& t, const std::vector<std::string>& all) {
    std::vector<std::string> kept;
    for (const std::string& kv : all)
        for (const ParamSpec& p : t.params)
            if (kv.rfind(p.name + "=", 0) == 0) kept.push_back(kv);
    return kept;
}

Scene loadShipped(const char* name, int w, int h) {
    Scene s = loadScene(std::string(SO_SCENES_DIR) + "/" + name + ".scene.json");
    s.camera.width = w;
    s.camera.height = h;
    return s;
}

TEST(Raster, CameraPassSeesWhatTheOracleSees) {
    REQUIRE_GL();
    for (const char* name : {"contact_box", "spot_objects", "terrain_sun"}) {
        Scene s = loadShipped(name, 200, 150);
        ChannelImage o = runQuiet(s), r = raster(s, "basic", {});
        size_t both = 0, same = 0, hitDiff = 0;
        for (size_t i = 0; i < o.pixelCount(); ++i) {
            const bool ho = o.channel(ch::kHit)[i] != 0.0f, hr = r.channel(ch::kHit)[i] != 0.0f;
            hitDiff += ho != hr;
            if (!ho || !hr) continue;
            ++both;
            same += o.channel(ch::kMeshId)[i] == r.channel(ch::kMeshId)[i] &&
                    o.channel(ch::kPrimId)[i] == r.channel(ch::kPrimId)[i];
        }
        std::printf(
            "[ camera ] %s: %zu of %zu pixels see the same triangle, %zu differ in hit/miss\n",
            name, same, both, hitDiff);
        EXPECT_GE(double(same) / double(both), 0.99) << name;
        EXPECT_LE(double(hitDiff) / double(o.pixelCount()), 0.002) << name;
    }
}

// The plumbing check: with acne biased away, the raster path agrees with the oracle wherever
// shadow mapping has no inherent error (away from shadow boundaries). Plain `basic` is measured
// too but held only to "never lights a shadowed pixel": on receivers tilted to the map a texel's
// stored depth differs from the receiver's by up to half a texel times tan(theta) at any depth
// precision, so it shows slope acne even at 4096 with a float map (issue 4 expected >= 99%; the
// measured figure is printed and reported).
TEST(Raster, AgreementAwayFromBoundariesAt4096) {
    REQUIRE_GL();
    Scene s = loadShipped("contact_box", 320, 240);
    ChannelImage o = runQuiet(s);
    Comparison basic =
        compare(o, raster(s, "basic", {"resolution=4096", "depth_format=32"}), "key", 2);
    Comparison slope =
        compare(o, raster(s, "slope-bias", {"resolution=4096", "depth_format=32"}), "key", 2);
    std::printf(
        "[ agreement ] 4096/32f, %zu pixels: basic %.4f (%zu false shadow, %zu false lit), "
        "slope-bias %.5f "
        "(%zu false shadow, %zu false lit)\n",
        basic.counted, basic.agreement(), basic.falseShadow, basic.falseLit, slope.agreement(),
        slope.falseShadow, slope.falseLit);
    ASSERT_GT(slope.oracleShadow, 2000u);
    EXPECT_GE(slope.agreement(), 0.99);
    EXPECT_LE(double(basic.falseLit) / double(basic.counted), 0.001);
}

// A plane lit at a grazing angle: basic shows acne, slope-bias removes it.
TEST(Raster, AcneAtGrazingAndSlopeBiasCuresIt) {
    REQUIRE_GL();
    Scene s;
    s.meshes.push_back(makeGrid({0, 0, 0}, {20, 0, 0}, {0, 0, -20}, 8, "plane"));
    const double el = 12.0 * std::numbers::pi / 180.0;
    s.lights = {directionalLight("sun", glm::dvec3(-std::cos(el), -std::sin(el), -0.2))};
    s.lights[0].wsDirection = glm::normalize(s.lights[0].wsDirection);
    s.camera.wsEye = {0, 12, 14};
    s.camera.wsTarget = {0, 0, 0};
    s.camera.width = 200;
    s.camera.height = 150;
    finalizeScene(s);
    ChannelImage o = runQuiet(s);
    Comparison basic = compare(o, raster(s, "basic", {"resolution=1024"}), "sun", 0);
    Comparison slope = compare(o, raster(s, "slope-bias", {"resolution=1024"}), "sun", 0);
    const double acneBasic = double(basic.falseShadow) / double(basic.oracleLit);
    const double acneSlope = double(slope.falseShadow) / double(slope.oracleLit);
    std::printf(
        "[ acne ] false shadow on oracle-lit pixels: basic %.4f, slope-bias %.5f (%zu pixels)\n",
        acneBasic, acneSlope, basic.oracleLit);
    ASSERT_GT(basic.oracleLit, 10000u);
    EXPECT_GT(acneBasic, 0.05);
    EXPECT_LT(acneSlope, 0.005);
}

// A large constant bias detaches the shadow from the box's base: lit pixels where the oracle
// has shadow, right at the contact.
TEST(Raster, LargeBiasPeterPans) {
    REQUIRE_GL();
    Scene s = loadShipped("contact_box", 320, 240);
    ChannelImage o = runQuiet(s);
    // The box is solid: the map holds its lit faces, some 2 units from the floor behind it along
    // the light's rays, so the shadow detaches only once the bias is of that order (300 texels is
    // about 1.5 units here).
    Comparison small = compare(o, raster(s, "bias", {"bias=1"}), "key", 0);
    Comparison large = compare(o, raster(s, "bias", {"bias=300"}), "key", 0);
    std::printf(
        "[ peter-panning ] false lit: bias=1 %zu, bias=300 %zu of %zu oracle-shadowed pixels\n",
        small.falseLit, large.falseLit, large.oracleShadow);
    EXPECT_GT(large.falseLit, 200u);
    EXPECT_GT(large.falseLit, 10 * std::max<size_t>(small.falseLit, 10));
}

// A point light inside a room with a ring of pillars and plates above and below it: shadows fall
// through all six cube faces. Agreement per face, and along the seams between faces.
TEST(Raster, CubeMapShadowsOnAllSixFacesWithoutSeams) {
    REQUIRE_GL();
    Scene s;
    s.meshes.push_back(makeGrid({0, 0, 0}, {14, 0, 0}, {0, 0, -14}, 8, "floor"));
    s.meshes.push_back(makeGrid({0, 3, 0}, {14, 0, 0}, {0, 0, 14}, 8, "ceiling"));
    for (int k = 0; k < 8; ++k) {
        const double a = 2 * std::numbers::pi * (k + 0.3) / 8;
        const glm::dvec3 c(2.0 * std::cos(a), 0, 2.0 * std::sin(a));
        s.meshes.push_back(
            makeBox(c + glm::dvec3(-0.2, 0.4, -0.2), c + glm::dvec3(0.2, 2.6, 0.2), "pillar"));
    }
    s.meshes.push_back(makeBox({-0.5, 0.4, -0.4}, {0.4, 0.5, 0.5}, "plate below"));
    s.meshes.push_back(makeBox({-0.4, 2.5, -0.5}, {0.5, 2.6, 0.4}, "plate above"));
    const glm::dvec3 light(0.1, 1.5, 0.05);
    s.lights = {pointLight("bulb", light)};
    s.camera.wsEye = {0.3, 1.5, 5.5};
    s.camera.wsTarget = {0.0, 1.5, 0.0};
    s.camera.vfovDeg = 110;
    s.camera.width = 320;
    s.camera.height = 240;
    finalizeScene(s);
    ChannelImage o = runQuiet(s), r = raster(s, "slope-bias", {"resolution=2048"});
    const float* Vo = o.channel("bulb.V");
    const float* Vr = r.channel("bulb.V");
    const float* Co = o.channel("bulb.cos");
    size_t counted[6] = {}, agree[6] = {}, shadowed[6] = {}, seam = 0, seamAgree = 0;
    for (size_t i = 0; i < o.pixelCount(); ++i) {
        if (o.channel(ch::kHit)[i] == 0.0f || Co[i] <= 0.0f ||
            o.channel(ch::kMeshId)[i] != r.channel(ch::kMeshId)[i] ||
            o.channel(ch::kPrimId)[i] != r.channel(ch::kPrimId)[i])
            continue;
        const glm::dvec3 v =
            glm::dvec3(o.channel(ch::kPX)[i], o.channel(ch::kPY)[i], o.channel(ch::kPZ)[i]) - light;
        const glm::dvec3 a = glm::abs(v);
        const int axis = a.x >= a.y && a.x >= a.z ? 0 : a.y >= a.z ? 1 : 2;
        const int face = 2 * axis + (v[axis] < 0 ? 1 : 0);
        const bool same = (Vo[i] > 0.5f) == (Vr[i] > 0.5f);
        ++counted[face];
        agree[face] += same;
        shadowed[face] += Vo[i] < 0.5f;
        // Near a seam: the two largest components within 2% of each other.
        double m[3] = {a.x, a.y, a.z};
        std::sort(m, m + 3);
        if (m[1] > 0.98 * m[2]) {
            ++seam;
            seamAgree += same;
        }
    }
    const char* names[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
    for (int f = 0; f < 6; ++f) {
        const double ag = counted[f] ? double(agree[f]) / double(counted[f]) : 0.0;
        std::printf("[ cube ] face %s: %zu pixels, %zu shadowed, agreement %.4f\n", names[f],
                    counted[f], shadowed[f], ag);
        EXPECT_GT(counted[f], 200u) << names[f];
        EXPECT_GT(shadowed[f], 20u) << names[f] << ": the face must carry shadows";
        EXPECT_GE(ag, 0.97) << names[f];
    }
    std::printf("[ cube ] %zu pixels within 2%% of a seam, agreement %.4f\n", seam,
                double(seamAgree) / double(std::max<size_t>(seam, 1)));
    EXPECT_GT(seam, 100u);
    EXPECT_GE(double(seamAgree) / double(seam), 0.97);
}

// Back faces in the map: no acne on the closed box scene without any bias.
TEST(Raster, BackFacesNeedNoBiasOnClosedGeometry) {
    REQUIRE_GL();
    Scene s = loadShipped("contact_box", 320, 240);
    ChannelImage o = runQuiet(s);
    Comparison c =
        compare(o, raster(s, "back-faces", {"resolution=4096", "depth_format=32"}), "key", 2);
    std::printf("[ back-faces ] agreement %.5f of %zu pixels (%zu false shadow, %zu false lit)\n",
                c.agreement(), c.counted, c.falseShadow, c.falseLit);
    EXPECT_GE(c.agreement(), 0.99);
}

// Two overlapping occluders at very different depths: where the oracle says umbra, VSM's Chebyshev
// bound over blurred moments lets light through (light bleeding); MSM's four moments far less at
// the same blur; PCF not at all.
TEST(Raster, VsmBleedsLightUnderOverlappingOccluders) {
    REQUIRE_GL();
    Scene s;
    s.meshes.push_back(makeGrid({0, 0, 0}, {12, 0, 0}, {0, 0, -12}, 4, "floor"));
    s.meshes.push_back(makeGrid({-0.5, 0.6, 0}, {3, 0, 0}, {0, 0, -3}, 1, "low plate"));
    s.meshes.push_back(makeGrid({0.8, 4.0, 0.3}, {3, 0, 0}, {0, 0, -3}, 1, "high plate"));
    s.lights = {directionalLight("sun", glm::normalize(glm::dvec3(0.15, -1.0, 0.1)))};
    // Low, so that the floor under both plates is in view.
    s.camera.wsEye = {-1, 2.2, 7};
    s.camera.wsTarget = {0.3, 0, 0};
    s.camera.width = 240;
    s.camera.height = 180;
    finalizeScene(s);
    ChannelImage o = runQuiet(s);
    // Umbra interior: floor pixels with oracle V = 0 at least 3 pixels from any other pixel, so
    // that the filtering every technique does at an umbra's edge does not count as bleeding.
    const int w = o.width(), h = o.height();
    const float* Vo = o.channel("sun.V");
    auto umbraAt = [&](int x, int y) {
        const size_t i = size_t(y) * size_t(w) + size_t(x);
        return o.channel(ch::kMeshId)[i] == 0.0f && Vo[i] == 0.0f;
    };
    auto bleeding = [&](const ChannelImage& r) {
        const float* Vr = r.channel("sun.V");
        size_t umbra = 0, bleed = 0;
        for (int y = 3; y < h - 3; ++y)
            for (int x = 3; x < w - 3; ++x) {
                bool interior = true;
                for (int dy = -3; dy <= 3 && interior; ++dy)
                    for (int dx = -3; dx <= 3 && interior; ++dx) interior = umbraAt(x + dx, y + dy);
                const size_t i = size_t(y) * size_t(w) + size_t(x);
                if (!interior || r.channel(ch::kMeshId)[i] != 0.0f) continue;
                ++umbra;
                bleed += Vr[i] > 0.1f;
            }
        return std::make_pair(umbra, bleed);
    };
    const auto [umbra, vsmBleed] =
        bleeding(raster(s, "vsm", {"resolution=1024", "blur=12", "bleed_reduction=0"}));
    const auto [umbra2, pcfBleed] = bleeding(raster(s, "pcf", {"resolution=1024", "kernel=7"}));
    const auto [umbra3, vsmReduced] =
        bleeding(raster(s, "vsm", {"resolution=1024", "blur=12", "bleed_reduction=0.5"}));
    // Four moments at the same blur bound the lit fraction more tightly (issue 14).
    const auto [umbra4, msmBleed] =
        bleeding(raster(s, "msm", {"resolution=1024", "blur=12", "bleed_reduction=0"}));
    (void)umbra2;
    (void)umbra3;
    (void)umbra4;
    std::printf("[ bleeding ] floor umbra pixels with V > 0.1: vsm %zu, msm %zu, pcf %zu of %zu\n",
                vsmBleed, msmBleed, pcfBleed, umbra);
    ASSERT_GT(umbra, 1000u);
    EXPECT_GT(vsmBleed, umbra / 50);
    EXPECT_LT(msmBleed, vsmBleed / 2);
    EXPECT_LT(pcfBleed, umbra / 500 + 1);
}

// Every technique compiles and renders for every kind of light map, and agrees with the oracle on
// most pixels away from shadow boundaries (filtered ones soften edges; none may be far off).
TEST(Raster, EveryTechniqueRendersEveryLightKind) {
    REQUIRE_GL();
    Scene s = loadShipped("spot_objects", 160, 120);
    s.lights.push_back(directionalLight("sun", glm::normalize(glm::dvec3(0.3, -1.0, 0.2))));
    ChannelImage o = runQuiet(s);
    for (const TechniqueInfo* t : allTechniques()) {
        ChannelImage r = raster(s, t->name, settingsFor(*t, {"resolution=1024"}));
        for (const Light& l : s.lights) {
            Comparison c = compare(o, r, l.name, 3);
            std::printf("[ techniques ] %-15s %-5s agreement %.4f of %zu\n", t->name.c_str(),
                        l.name.c_str(), c.agreement(), c.counted);
            // basic, a constant bias (which cannot follow the slope) and polygon-offset
            // (driver-defined units) may show acne; the slope-aware and filtered ones must not.
            if (t->name != "basic" && t->name != "bias" && t->name != "polygon-offset") {
                EXPECT_GE(c.agreement(), 0.97) << t->name << " " << l.name;
            }
            EXPECT_GT(c.counted, 1000u);
        }
    }
}

// A directional map fitted only to the receivers in view: smaller texels, and no occluder lost.
TEST(Raster, DirectionalFitToVisibleReceivers) {
    REQUIRE_GL();
    Scene s = loadShipped("terrain_sun", 200, 150);
    s.camera.vfovDeg = 15;  // a close-up of part of the terrain
    std::string why;
    RasterOptions o;
    o.frames = 1;
    o.warmup = 0;
    RasterResult whole =
        renderRaster(s, *createTechnique("slope-bias", {"resolution=1024"}), o, *glContext(why));
    RasterResult fitted = renderRaster(
        s, *createTechnique("slope-bias", {"resolution=1024", "fit=1"}), o, *glContext(why));
    ASSERT_TRUE(whole.stats.lights[0].texelSizeIsAbsolute);
    const double texelWhole = whole.stats.lights[0].texelSize;
    const double texelFitted = fitted.stats.lights[0].texelSize;
    ChannelImage oracle = runQuiet(s);
    Comparison cw = compare(oracle, whole.image, "sun", 2),
               cf = compare(oracle, fitted.image, "sun", 2);
    std::printf(
        "[ fit ] texel %.5f -> %.5f; agreement away from boundaries %.4f -> %.4f (%zu pixels)\n",
        texelWhole, texelFitted, cw.agreement(), cf.agreement(), cf.counted);
    EXPECT_LT(texelFitted, 0.8 * texelWhole);
    EXPECT_GE(cf.agreement(), 0.99);
    EXPECT_GE(cf.agreement(), cw.agreement() - 0.001);
}

// issue 5's end-to-end expectations, through the compare command on a shipped scene.
TEST(Compare, EndToEndOnTheContactScene) {
    REQUIRE_GL();
    const std::string out = "/tmp/so_compare_e2e_" + std::to_string(::getpid());
    const std::string cmd =
        std::string(SO_CLI_PATH) + " compare " + SO_SCENES_DIR +
        "/contact_box.scene.json --width 320 --height 240 --frames 1 --no-cache --embed-images "
        "--out " +
        out +
        " --technique basic:resolution=1024 --technique slope-bias:resolution=1024 --technique "
        "bias:bias=1"
        " --technique bias:bias=300 --technique pcf:resolution=1024,kernel=5"
        " --technique slope-bias:resolution=512 > /dev/null 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    std::ifstream in(out + "/metrics.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    auto metric = [&](const std::string& label, const std::string& name) {
        for (const auto& r : j["results"])
            if (r["label"] == label) return r["lights"]["key"][name];
        ADD_FAILURE() << label;
        return nlohmann::json();
    };
    const double acneBasic = metric("basic:resolution=1024", "acne_rate").get<double>();
    const double acneSlope = metric("slope-bias:resolution=1024", "acne_rate").get<double>();
    const double ppSmall = metric("bias:bias=1", "peter_panning_rate").get<double>();
    const double ppLarge = metric("bias:bias=300", "peter_panning_rate").get<double>();
    const double p95Basic =
        metric("basic:resolution=1024", "boundary_displacement_px")["p95"].get<double>();
    const double p95Pcf =
        metric("pcf:resolution=1024,kernel=5", "boundary_displacement_px")["p95"].get<double>();
    std::printf(
        "[ compare ] acne basic %.4f vs slope-bias %.4f; peter-panning bias=1 %.4f vs bias=300 "
        "%.4f; "
        "boundary p95 basic %.2f vs pcf %.2f px\n",
        acneBasic, acneSlope, ppSmall, ppLarge, p95Basic, p95Pcf);
    EXPECT_LT(acneSlope, acneBasic);
    EXPECT_GT(ppLarge, ppSmall);
    EXPECT_LT(p95Pcf, p95Basic);
    // The report: one file that needs nothing else, with the oracle, each technique and its error
    // map inline, the chart and the table.
    std::ifstream rin(out + "/report.html");
    const std::string report((std::istreambuf_iterator<char>(rin)), {});
    auto count = [&](const std::string& needle) {
        size_t n = 0;
        for (size_t at = report.find(needle); at != std::string::npos;
             at = report.find(needle, at + 1))
            ++n;
        return n;
    };
    // The oracle and the predicted aliasing once; per technique its render, its error map and the
    // worst region (technique and oracle).
    EXPECT_EQ(count("<img "), 2u + 4u * 6u);
    EXPECT_EQ(count("src=\"data:image/png;base64,"), count("<img "));
    EXPECT_EQ(count("http://") - count("http://www.w3.org/2000/svg") + count("https://") +
                  count("<link") + count("src=\"/"),
              0u)
        << "self-contained";
    EXPECT_EQ(count("<svg class=\"chart\""), 1u) << "one light, one chart (drawn by the script)";
    EXPECT_EQ(count("<table class=\"sortable summary\">"), 1u);
    // The two slope-bias settings differ only in the shadow maps' quality parameter, resolution:
    // one curve key, two quality values, in the data the chart is drawn from.
    EXPECT_EQ(count("\"curve\":\"slope-bias blend=0.1 cascades=1 contact=0 "
                    "contact_bilinear_threshold=0.02 contact_contrast=4 contact_distance=0.3 "
                    "contact_fade_samples=8 contact_hard_samples=4 contact_ignore_edges=0 "
                    "contact_method=0 contact_samples=60 contact_steps=16 "
                    "contact_surface_thickness=0.005 contact_thickness=0.1 depth_format=24 fit=0 "
                    "max=10 min=0.1 slope_factor=1 snap=1 split_lambda=0.5"),
              2u);
    EXPECT_EQ(count("\"quality\":512"), 1u);
    // A budget table per cost axis (times, memory, work), frame time's shown.
    EXPECT_EQ(count("<table class=\"budget\">"), 11u);  // work.rays_traced the 11th
    EXPECT_EQ(count("<div class=\"budget-box\" data-cost=\"frame_ms\">"), 1u);
    EXPECT_EQ(count("<div class=\"budget-box\" data-cost=\"work.bytes_moved\" hidden>"), 1u);
    EXPECT_NE(report.find("id=\"metrics\">"), std::string::npos);
    EXPECT_NE(report.find("Times were measured on <b>" + j["gl"]["renderer"].get<std::string>()),
              std::string::npos)
        << "the report says which renderer measured the times";
    // Parameters keep their types; timings carry their spread.
    for (const auto& r : j["results"]) {
        EXPECT_TRUE(r["parameters"]["resolution"].is_number_integer()) << r["label"];
        EXPECT_EQ(r["timings"]["frames"], 1) << "as asked";
        EXPECT_EQ(r["timings"]["interleaved_with"], 6);
        for (const auto& [light, m] : r["lights"].items()) {
            const auto& cost = m["cost"];
            EXPECT_LE(cost["shadow_map_ms_p25"].get<double>(), cost["shadow_map_ms"].get<double>());
            EXPECT_LE(cost["shadow_map_ms"].get<double>(), cost["shadow_map_ms_p75"].get<double>());
            EXPECT_TRUE(cost["noisy"].is_boolean());
            EXPECT_GT(cost["memory_bytes"].get<uint64_t>(), 1024u * 1024u * 4u);
        }
    }
    // The wide CSV: a header and one row per light x technique, parameters as columns.
    std::ifstream win(out + "/metrics_wide.csv");
    std::string header, line;
    std::getline(win, header);
    size_t rows = 0;
    while (std::getline(win, line)) ++rows;
    EXPECT_EQ(header.rfind("scene,light,technique,label,", 0), 0u) << header;
    for (const char* column : {"param.resolution", "param.kernel", "acne_rate", "cost.frame_ms"})
        EXPECT_NE(header.find(column), std::string::npos) << column;
    EXPECT_EQ(rows, 6u * j["results"][0]["lights"].size());
    std::filesystem::remove_all(out);
}

// A technique that casts no shadow (back-faces on a single-sided occluder) must not look best:
// its boundary displacement is the worst there is, and its wrong pixels are all coloured.
TEST(Compare, MissingShadowIsTheWorstNotTheBest) {
    REQUIRE_GL();
    const std::string out = "/tmp/so_compare_missing_" + std::to_string(::getpid());
    const std::string cmd = std::string(SO_CLI_PATH) + " compare " + SO_SCENES_DIR +
                            "/penumbra_square.scene.json --width 160 --height 120 --frames 1 "
                            "--no-cache --out " +
                            out + " --technique back-faces --technique pcf > /dev/null 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    std::ifstream in(out + "/metrics.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    const auto& backFaces = j["results"][0]["lights"].begin().value();
    const auto& pcf = j["results"][1]["lights"].begin().value();
    const double diagonal = std::hypot(160.0, 120.0);
    EXPECT_TRUE(backFaces["boundary_displacement_px"]["missing_boundary"].get<bool>());
    EXPECT_NEAR(backFaces["boundary_displacement_px"]["p95"].get<double>(), diagonal, 1e-9);
    EXPECT_LT(pcf["boundary_displacement_px"]["p95"].get<double>(), diagonal / 4);
    EXPECT_TRUE(backFaces["aliasing_rate"].is_null()) << "an area light has no 0/1 edge";
    EXPECT_GT(backFaces["false_lit_rate"].get<double>(), 0.05);
    std::filesystem::remove_all(out);
}

// A minimal well-formedness check: balanced tags, one root, quoted attributes.
bool wellFormedXml(const std::string& x) {
    std::vector<std::string> stack;
    size_t i = x.find("?>");
    if (x.rfind("<?xml", 0) != 0 || i == std::string::npos) return false;
    int roots = 0;
    for (i += 2; (i = x.find('<', i)) != std::string::npos;) {
        const size_t end = x.find('>', i);
        if (end == std::string::npos) return false;
        std::string tag = x.substr(i + 1, end - i - 1);
        if (std::count(tag.begin(), tag.end(), '"') % 2) return false;
        if (tag[0] == '/') {
            if (stack.empty() || stack.back() != tag.substr(1)) return false;
            stack.pop_back();
        } else if (tag.back() != '/') {
            if (stack.empty()) ++roots;
            stack.push_back(tag.substr(0, tag.find(' ')));
        }
        i = end + 1;
    }
    return stack.empty() && roots == 1;
}

int runCli(const std::string& args, std::string* output = nullptr) {
    const std::string log = "/tmp/so_gate_" + std::to_string(::getpid()) + ".log";
    const int status =
        std::system((std::string(SO_CLI_PATH) + " " + args + " > " + log + " 2>&1").c_str());
    if (output) {
        std::ifstream in(log);
        output->assign(std::istreambuf_iterator<char>(in), {});
    }
    std::filesystem::remove(log);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The shipped scenes, gated with the shipped example limits; and the gate's exit codes.
TEST(Gate, ShippedScenesPassTheExampleLimitsAndTheExitCodesHold) {
    REQUIRE_GL();
    const std::string dir = "/tmp/so_gate_" + std::to_string(::getpid());
    ASSERT_EQ(
        runCli("compare " SO_SCENES_DIR
               "/contact_box.scene.json --width 240 --height 180 --frames 1 --no-cache --out " +
               dir +
               " --technique basic --technique slope-bias --technique pcf:kernel=5 --technique "
               "bias:bias=300"),
        0);
    std::string out;
    // The example limits: everything but the large bias passes; it peter-pans.
    EXPECT_EQ(
        runCli("gate " + dir + "/metrics.json --limits " SO_SCENES_DIR "/limits.json --junit " +
                   dir + "/gate.xml",
               &out),
        1)
        << out;
    EXPECT_NE(out.find("FAIL contact_box.scene.json key bias:bias=300 peter_panning_rate"),
              std::string::npos)
        << out;
    // Every failing line is the large bias's (it peter-pans and its shadow edge is displaced);
    // one line per failing limit, then the summary.
    std::istringstream lines(out);
    size_t failLines = 0;
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind("FAIL ", 0) != 0) continue;
        ++failLines;
        EXPECT_NE(line.find("bias:bias=300"), std::string::npos) << line;
    }
    EXPECT_NE(out.find(std::to_string(failLines) + " failed"), std::string::npos) << out;
    std::ifstream xin(dir + "/gate.xml");
    const std::string xml((std::istreambuf_iterator<char>(xin)), {});
    EXPECT_TRUE(wellFormedXml(xml)) << xml;
    EXPECT_NE(xml.find("<failure"), std::string::npos);
    // Limits that hold: exit 0.
    std::ofstream(dir + "/loose.json") << R"({"limits_format": 1, "default": {"acne_rate": 1.0}})";
    EXPECT_EQ(runCli("gate " + dir + "/metrics.json --limits " + dir + "/loose.json", &out), 0)
        << out;
    // A limit on a metric that is null here (bleeding of unfiltered techniques) is counted as not
    // applicable, not silently as a pass.
    std::ofstream(dir + "/na.json")
        << R"({"limits_format": 1, "default": {"light_bleeding_rate": 0.0}})";
    EXPECT_EQ(runCli("gate " + dir + "/metrics.json --limits " + dir + "/na.json --junit " + dir +
                         "/na.xml",
                     &out),
              0)
        << out;
    EXPECT_NE(out.find("(4 of them not applicable"), std::string::npos) << out;
    std::ifstream nain(dir + "/na.xml");
    const std::string naXml((std::istreambuf_iterator<char>(nain)), {});
    EXPECT_TRUE(wellFormedXml(naXml)) << naXml;
    EXPECT_NE(naXml.find("<skipped"), std::string::npos) << naXml;
    // Bad input: exit 2 with one line naming the file and field.
    std::ofstream(dir + "/typo.json") << R"({"limits_format": 1, "default": {"acne_rat": 0.1}})";
    EXPECT_EQ(runCli("gate " + dir + "/metrics.json --limits " + dir + "/typo.json", &out), 2)
        << out;
    EXPECT_NE(out.find("typo.json: default.acne_rat: unknown metric"), std::string::npos) << out;
    std::ofstream(dir + "/broken.json") << "{ not json";
    EXPECT_EQ(runCli("gate " + dir + "/metrics.json --limits " + dir + "/broken.json", &out), 2)
        << out;
    EXPECT_EQ(runCli("gate " + dir + "/nope.json --limits " + dir + "/loose.json", &out), 2) << out;
    std::filesystem::remove_all(dir);
}

// The shipped scenes, compared with the slope-aware techniques at the demo's resolution, pass the
// shipped example limits.
TEST(Gate, ShippedScenesPassTheExampleLimits) {
    REQUIRE_GL();
    const std::string dir = "/tmp/so_gate_shipped_" + std::to_string(::getpid());
    for (const char* name :
         {"contact_box", "penumbra_square", "sphere_light", "spot_objects", "terrain_sun"}) {
        std::string out;
        ASSERT_EQ(runCli(std::string("compare " SO_SCENES_DIR "/") + name +
                             ".scene.json --width 480 --height 360 --frames 1 --cache " + dir +
                             "/cache --out " + dir + "/" + name +
                             " --technique slope-bias --technique pcf:kernel=5",
                         &out),
                  0)
            << out;
        EXPECT_EQ(runCli("gate " + dir + "/" + name +
                             "/metrics.json --limits " SO_SCENES_DIR "/limits.json",
                         &out),
                  0)
            << name << ": " << out;
    }
    std::filesystem::remove_all(dir);
}

// The predicted aliasing is texel over pixel footprint: a map with 4x fewer texels per side gives
// exactly 4x the prediction on every pixel.
TEST(Raster, PredictedAliasingScalesWithResolution) {
    REQUIRE_GL();
    Scene s = loadShipped("spot_objects", 160, 120);
    ChannelImage fine = raster(s, "slope-bias", {"resolution=2048"}),
                 coarse = raster(s, "slope-bias", {"resolution=512"});
    for (const Light& l : s.lights) {
        const float* a = fine.channel(ch::lightChannel(l.name, ch::kPredictedAliasing));
        const float* b = coarse.channel(ch::lightChannel(l.name, ch::kPredictedAliasing));
        size_t n = 0;
        for (size_t i = 0; i < fine.pixelCount(); ++i) {
            if (!(a[i] > 0.0f)) continue;
            ++n;
            ASSERT_NEAR(b[i] / a[i], 4.0f, 1e-4f) << l.name << " pixel " << i;
        }
        EXPECT_GT(n, 5000u) << l.name;
    }
}

TEST(Gate, GlobPatterns) {
    EXPECT_TRUE(globMatch("*", "anything"));
    EXPECT_TRUE(globMatch("pcf*", "pcf:kernel=5"));
    EXPECT_TRUE(globMatch("contact_box*", "contact_box.scene.json"));
    EXPECT_TRUE(globMatch("b?sic", "basic"));
    EXPECT_FALSE(globMatch("pcf", "pcf:kernel=5"));
    EXPECT_FALSE(globMatch("*.gltf", "scene.json"));
}

TEST(Raster, TechniquesRejectUnknownKeysAndOutOfRangeValues) {
    for (const TechniqueInfo* t : allTechniques()) {
        auto create = [&](const std::vector<std::string>& settings) {
            return createTechnique(t->name, settings);
        };
        EXPECT_THROW(create({"no_such_key=1"}), InputError) << t->name;
        EXPECT_THROW(create({"resolution=8"}), InputError) << t->name;
        EXPECT_THROW(create({"resolution=abc"}), InputError) << t->name;
        EXPECT_THROW(create({"depth_format=20"}), InputError) << t->name;
        EXPECT_THROW(create({"resolution"}), InputError) << t->name;
        for (const ParamSpec& p : t->params) {
            EXPECT_THROW(create({p.name + "=" + std::to_string(p.max * 2 + 1)}), InputError)
                << t->name << " " << p.name;
            // A parameter that needs another setting is given with it (ParamSpec::needs).
            std::vector<std::string> settings = {p.name + "=" + std::to_string(p.defaultValue)};
            // (Unless the defaults meet it: pcf's slope_factor needs bias=slope, its default.)
            if (!needsMet(p, t->params, create({})->values())) {
                EXPECT_THROW(create(settings), InputError) << t->name << " " << p.name;
                const std::vector<std::string> needed = neededSettings(p, t->params);
                settings.insert(settings.begin(), needed.begin(), needed.end());
            }
            EXPECT_NO_THROW(create(settings)) << t->name << " " << p.name;
        }
        try {
            create({"bogus=1"});
            ADD_FAILURE() << t->name << " accepted bogus=1";
        } catch (const InputError& e) {
            // The valid keys are listed (or that there are none).
            const std::string listed = t->params.empty() ? "no parameters" : t->params[0].name;
            EXPECT_NE(std::string(e.what()).find(listed), std::string::npos)
                << t->name << ": " << e.what();
        }
    }
    EXPECT_THROW(createTechnique("nope", {}), InputError);
    EXPECT_THROW(createTechnique("pcf", {"kernel=4"}), InputError) << "an even kernel";
}

// Parameters that pick a method take their names, and the numbers they took before names; any
// other word is an error that lists the names.
TEST(Raster, MethodParametersTakeNamesAndTheirNumbers) {
    size_t named = 0;
    for (const TechniqueInfo* t : allTechniques())
        for (const ParamSpec& p : t->params) {
            if (p.names.empty()) continue;
            ++named;
            EXPECT_EQ(p.min, 0.0) << t->name << " " << p.name;
            EXPECT_EQ(p.max, double(p.names.size() - 1)) << t->name << " " << p.name;
            const auto with = [&](const std::string& setting) {
                std::vector<std::string> settings = neededSettings(p, t->params);
                settings.push_back(setting);
                return settings;
            };
            for (size_t k = 0; k < p.names.size(); ++k) {
                const auto byName = createTechnique(t->name, with(p.name + "=" + p.names[k]));
                const auto byNumber =
                    createTechnique(t->name, with(p.name + "=" + std::to_string(k)));
                EXPECT_EQ(byName->values().real(p.name), double(k)) << t->name << " " << p.name;
                EXPECT_EQ(byName->values().all(), byNumber->values().all()) << t->name;
                EXPECT_EQ(paramValueText(p, double(k)), p.names[k]);
            }
            try {
                createTechnique(t->name, with(p.name + "=sideways"));
                ADD_FAILURE() << t->name << " accepted " << p.name << "=sideways";
            } catch (const InputError& e) {
                EXPECT_NE(std::string(e.what()).find("unknown value \"sideways\" (valid: " +
                                                     p.names[0] + ", " + p.names[1]),
                          std::string::npos)
                    << e.what();
            }
        }
    EXPECT_GE(named, 9u);  // fit, snap (every shadow map), method, bilateral, pattern x2, ...
    const auto pcf = createTechnique("pcf", {"pattern=poisson", "kernel=5"});
    EXPECT_EQ(pcf->values().integer("pattern"), 1);
    EXPECT_THROW(createTechnique("pcf", {"kernel=grid"}), InputError) << "names only where named";
}

// Every registered technique constructs at its defaults, reports every parameter of its table,
// and a created technique is of the family it is listed under.
TEST(Raster, RegistryListsEveryTechniqueWithItsTable) {
    const std::vector<const TechniqueInfo*> all = allTechniques();
    EXPECT_GE(all.size(), 11u);
    for (const TechniqueInfo* t : all) {
        const std::unique_ptr<Technique> created = createTechnique(t->name, {});
        EXPECT_EQ(created->name(), t->name);
        // Every parameter but those of an axis's plug-ins not chosen (depth_bias.h).
        size_t listed = 0;
        for (const ParamSpec& p : t->params) {
            if (p.pluginParam && !needsMet(p, t->params, created->values())) {
                EXPECT_EQ(created->values().all().count(p.name), 0u) << t->name << " " << p.name;
                continue;
            }
            ++listed;
            EXPECT_EQ(created->values().real(p.name), p.defaultValue) << t->name << " " << p.name;
        }
        EXPECT_EQ(created->values().all().size(), listed) << t->name;
        if (t->family == ShadowMapTechnique::kFamily) {
            EXPECT_NE(dynamic_cast<const ShadowMapTechnique*>(created.get()), nullptr) << t->name;
        }
    }
}

// A setting reaches the shader at full precision: std::to_string once made min_variance=1e-7 the
// literal 0.000000.
TEST(Raster, ShaderNumbersKeepFullPrecision) {
    for (const char* value : {"1e-07", "1.2345678901234567e-05", "0.0099999999999999985"}) {
        const std::unique_ptr<Technique> vsm =
            createTechnique("vsm", {std::string("min_variance=") + value});
        const std::string defines = dynamic_cast<const ShadowMapTechnique&>(*vsm).shaderDefines();
        const std::string key = "#define MIN_VARIANCE ";
        const size_t at = defines.find(key);
        ASSERT_NE(at, std::string::npos) << defines;
        const std::string literal =
            defines.substr(at + key.size(), defines.find('\n', at) - at - key.size());
        EXPECT_EQ(std::strtod(literal.c_str(), nullptr), std::strtod(value, nullptr))
            << "literal " << literal << " for " << value;
    }
    EXPECT_EQ(glslFloat(1.0), "1.0") << "GLSL reads 1 as an int";
    EXPECT_EQ(glslFloat(1e-7), "9.9999999999999995e-08");
    EXPECT_EQ(std::strtod(glslFloat(0.1).c_str(), nullptr), 0.1);
}

// With the smallest variance floor the Chebyshev bound must see it: min_variance=1e-7 and 1e-3
// render different images (with to_string both were 0.000000 and 0.001000; 1e-7 was lost).
TEST(Raster, SmallVarianceFloorReachesTheShader) {
    REQUIRE_GL();
    Scene s = loadShipped("contact_box", 160, 120);
    const ChannelImage tiny = raster(s, "vsm", {"resolution=256", "min_variance=1e-7"});
    const ChannelImage zero = raster(s, "vsm", {"resolution=256", "min_variance=0"});
    const float* a = tiny.channel(ch::lightChannel(s.lights[0].name, ch::kVisibility));
    const float* b = zero.channel(ch::lightChannel(s.lights[0].name, ch::kVisibility));
    size_t differ = 0;
    for (size_t i = 0; i < tiny.pixelCount(); ++i) differ += a[i] != b[i];
    EXPECT_GT(differ, 0u) << "min_variance=1e-7 rendered exactly as min_variance=0";
}

// ---- shadow volumes ---------------------------------------------------------------------------

// The volumes' geometry on its own: a closed box keeps the quads of its silhouette (twice: one
// per side), an open quad those of its four edges, whichever way it is wound; and the count of
// volumes around a point is the triangles between it and the light.
TEST(ShadowVolume, GeometryOfClosedAndOpenMeshes) {
    Scene box;
    box.meshes.push_back(makeBox({-1, 1, -1}, {1, 3, 1}, "box"));
    finalizeScene(box);
    const LocalFrame frame = LocalFrame::fit(box.wsBounds);
    const glm::dvec4 above(frame.lsFromWs({0.25, 8, 0.125}), 1.0);
    const WeldedScene welded = WeldedScene::build(box, frame);
    EXPECT_EQ(welded.lsPositions.size(), 8u);
    const ShadowVolumeGeometry g = buildShadowVolumes(welded, above);
    EXPECT_EQ(g.casters, 12u);
    // Seen from above, the silhouette is the top face's outline: 4 edges, 2 quads each.
    EXPECT_EQ(g.quads, 8u);
    // The same box with every triangle's corners its own vertices (as a glTF split at seams is):
    // welded back, the same volumes.
    Scene split = box;
    MeshPrimitive& m = split.meshes[0];
    std::vector<glm::dvec3> corners;
    for (uint32_t i : m.indices) corners.push_back(m.wsPositions[i]);
    m.wsPositions = corners;
    for (size_t i = 0; i < m.indices.size(); ++i) m.indices[i] = uint32_t(i);
    const WeldedScene weldedSplit = WeldedScene::build(split, frame);
    EXPECT_EQ(weldedSplit.lsPositions.size(), 8u);
    EXPECT_EQ(buildShadowVolumes(weldedSplit, above).quads, 8u);
    EXPECT_EQ(volumesContaining(welded, above, frame.lsFromWs({0, 0.5, 0})), 2);
    EXPECT_EQ(volumesContaining(welded, above, frame.lsFromWs({3, 0.5, 0})), 0);
    for (bool flip : {false, true}) {
        Scene quad;
        quad.meshes.push_back(makeGrid({0, 2, 0}, {2, 0, 0}, {0, 0, flip ? 2.0 : -2.0}, 1, "q"));
        finalizeScene(quad);
        const LocalFrame qf = LocalFrame::fit(quad.wsBounds);
        const WeldedScene wq = WeldedScene::build(quad, qf);
        const ShadowVolumeGeometry q =
            buildShadowVolumes(wq, glm::dvec4(qf.lsFromWs({0.25, 8, 0.125}), 1.0));
        EXPECT_EQ(q.casters, 2u) << flip;
        EXPECT_EQ(q.quads, 4u) << flip;  // the diagonal cancels
        EXPECT_EQ(volumesContaining(wq, glm::dvec4(qf.lsFromWs({0.25, 8, 0.125}), 1.0),
                                    qf.lsFromWs({0.1, 0, 0.1})),
                  1)
            << flip;
    }
}

// A closed cube over a plane under a point light, the camera outside the cube's shadow and inside
// it: every volume technique agrees with the oracle on >= 99.9% of the pixels more than a pixel
// from a shadow boundary, except the naive z-pass (count started at 0) with the eye in the shadow,
// which inverts it.
TEST(Raster, ShadowVolumesExactWithTheCameraOutsideAndInside) {
    REQUIRE_GL();
    Scene s;
    s.meshes.push_back(makeGrid({0, 0, 0}, {24, 0, 0}, {0, 0, -24}, 8, "ground"));
    s.meshes.push_back(makeBox({-1, 1.5, -1}, {1, 3.5, 1}, "cube"));
    s.lights = {pointLight("lamp", {0.375, 9, 0.25})};
    s.camera.width = 240;
    s.camera.height = 180;
    s.camera.vfovDeg = 60;
    for (bool inside : {false, true}) {
        s.camera.wsEye = inside ? glm::dvec3(0.125, 0.75, 0.25) : glm::dvec3(-6, 7, 9);
        s.camera.wsTarget = inside ? glm::dvec3(4, 0, 2) : glm::dvec3(0, 0.5, 0);
        finalizeScene(s);
        ChannelImage o = runQuiet(s);
        for (const char* t : {"volume-zpass", "volume-zfail", "volume-zpass:init_count=0"}) {
            const std::string spec = t;
            const size_t colon = spec.find(':');
            const std::vector<std::string> settings =
                colon == std::string::npos ? std::vector<std::string>{}
                                           : std::vector<std::string>{spec.substr(colon + 1)};
            Comparison c = compare(o, raster(s, spec.substr(0, colon), settings), "lamp", 1);
            std::printf("[ volumes ] camera %s, %-26s agreement %.5f of %zu (%zu in shadow)\n",
                        inside ? "inside " : "outside", t, c.agreement(), c.counted,
                        c.oracleShadow);
            ASSERT_GT(c.oracleShadow, 500u);
            ASSERT_GT(c.oracleLit, 500u);
            if (inside && spec == "volume-zpass:init_count=0")
                EXPECT_LT(c.agreement(), 0.5) << "the naive z-pass must fail visibly";
            else
                EXPECT_GE(c.agreement(), 0.999) << t;
        }
    }
}

// An open mesh, a single quad wound away from the light, and the shipped hard-light scenes: the
// volumes stay exact.
TEST(Raster, ShadowVolumesOnOpenMeshesAndShippedScenes) {
    REQUIRE_GL();
    Scene quad;
    quad.meshes.push_back(makeGrid({0, 0, 0}, {16, 0, 0}, {0, 0, -16}, 4, "ground"));
    quad.meshes.push_back(makeGrid({0, 2, 0}, {3, 0, 0}, {0, 0, 3}, 1, "quad"));  // faces down
    quad.lights = {pointLight("lamp", {0.5, 7, 0.25})};
    quad.camera.wsEye = {-4, 8, 9};
    quad.camera.wsTarget = {0, 0, 0};
    quad.camera.width = 200;
    quad.camera.height = 150;
    finalizeScene(quad);
    std::vector<std::pair<std::string, Scene>> scenes = {{"open quad", quad}};
    for (const char* name : {"contact_box", "spot_objects", "terrain_sun"})
        scenes.emplace_back(name, loadShipped(name, 240, 180));
    for (const auto& [name, s] : scenes) {
        ChannelImage o = runQuiet(s);
        for (const char* t : {"volume-zpass", "volume-zfail"}) {
            ChannelImage r = raster(s, t, {});
            for (const Light& l : s.lights) {
                Comparison c = compare(o, r, l.name, 1);
                std::printf("[ volumes ] %-12s %-13s %-5s agreement %.5f of %zu\n", name.c_str(), t,
                            l.name.c_str(), c.agreement(), c.counted);
                EXPECT_GT(c.oracleShadow, 100u) << name << " " << l.name;
                EXPECT_GE(c.agreement(), 0.999) << name << " " << t << " " << l.name;
            }
        }
    }
}

// A real scanned mesh (the Stanford bunny, from Debian's libcgal-demo): 75,408 triangles whose
// silhouette is long and ragged.
TEST(Raster, ShadowVolumesOnTheBunny) {
    REQUIRE_GL();
    std::string why;
    const MeshPrimitive* bunny = cgalBunny(why);
    if (!bunny) GTEST_SKIP() << why;
    Scene s = makeBunnyScene(*bunny, 240, 180);
    s.lights = {pointLight("lamp", {4, 14, 6}),
                directionalLight("sun", glm::normalize(glm::dvec3(-0.5, -1.0, -0.375)))};
    finalizeScene(s);
    ChannelImage o = runQuiet(s);
    for (const char* t : {"volume-zpass", "volume-zfail"}) {
        ChannelImage r = raster(s, t, {});
        for (const Light& l : s.lights) {
            Comparison c = compare(o, r, l.name, 1);
            std::printf("[ volumes ] bunny %-13s %-5s agreement %.5f of %zu (%zu in shadow)\n", t,
                        l.name.c_str(), c.agreement(), c.counted, c.oracleShadow);
            EXPECT_GT(c.oracleShadow, 1000u);
            EXPECT_GE(c.agreement(), 0.999) << t << " " << l.name;
        }
    }
}

// ---- planar projected shadows and shadow textures --------------------------------------------

// The receivers' shadowed pixels of light `light` and their V in the raster image, where the
// oracle says umbra on mesh `mesh`.
std::vector<float> shadowValuesOn(const ChannelImage& o, const ChannelImage& r,
                                  const std::string& light, float mesh) {
    std::vector<float> v;
    const float* Vo = o.channel(ch::lightChannel(light, ch::kVisibility));
    const float* Vr = r.channel(ch::lightChannel(light, ch::kVisibility));
    for (size_t i = 0; i < o.pixelCount(); ++i)
        if (o.channel(ch::kHit)[i] != 0.0f && o.channel(ch::kMeshId)[i] == mesh &&
            r.channel(ch::kMeshId)[i] == mesh && Vo[i] == 0.0f &&
            o.channel(ch::lightChannel(light, ch::kCosine))[i] > 0.0f)
            v.push_back(Vr[i]);
    return v;
}

// Planar shadows on the shipped contact_box (the floor is the largest planar mesh): right where
// the oracle has them; at alpha 0.5 the stencil darkens each pixel once (V = 0.5 exactly), and
// without it the box's overlapping projected faces darken twice and more.
TEST(Raster, PlanarShadowsWithAndWithoutStencil) {
    REQUIRE_GL();
    Scene s = loadShipped("contact_box", 240, 180);
    ChannelImage o = runQuiet(s);
    Comparison c = compare(o, raster(s, "planar", {}), "key", 1);
    std::printf("[ planar ] contact_box agreement %.5f of %zu\n", c.agreement(), c.counted);
    EXPECT_GE(c.agreement(), 0.99);
    const std::vector<float> once =
        shadowValuesOn(o, raster(s, "planar", {"opacity=0.5"}), "key", 0.0f);
    const std::vector<float> twice =
        shadowValuesOn(o, raster(s, "planar", {"opacity=0.5", "stencil=0"}), "key", 0.0f);
    ASSERT_GT(once.size(), 500u);
    size_t onceExact = 0, twiceDarker = 0;
    for (float v : once) onceExact += v == 0.5f;
    for (float v : twice) twiceDarker += v <= 0.25f + 1e-6f;
    std::printf(
        "[ planar ] alpha 0.5 on %zu floor pixels in the box's shadow: with stencil %zu at "
        "exactly 0.5, without %zu at 0.25 or darker\n",
        once.size(), onceExact, twiceDarker);
    EXPECT_GE(double(onceExact) / double(once.size()), 0.99);
    EXPECT_GE(double(twiceDarker) / double(twice.size()), 0.5);
}

// A tall box shades a small one beside it, and a box under the floor must shade nothing: the
// planar and shadow-texture techniques put no shadow on the small box (the oracle has one: false
// lit, counted); the planar one projects nothing from below the plane, the shadow texture does.
TEST(Raster, PlanarAndShadowTextureMissShadowsOffTheReceiver) {
    REQUIRE_GL();
    Scene s;
    s.meshes.push_back(makeGrid({0, 0, 0}, {16, 0, 0}, {0, 0, -16}, 4, "ground"));
    s.meshes.push_back(makeBox({-1, 0, -1}, {1, 4, 1}, "tall"));
    s.meshes.push_back(makeBox({1.75, 0, -0.75}, {3.25, 1, 0.75}, "small"));
    s.meshes.push_back(makeBox({-3, -2, 3}, {-1, -0.5, 5}, "buried"));
    s.lights = {directionalLight("sun", glm::normalize(glm::dvec3(1.0, -0.75, 0.125))),
                pointLight("lamp", {-3.5, 6, 0.25})};
    s.camera.wsEye = {3, 7, 10};
    s.camera.wsTarget = {1, 0.5, 0};
    s.camera.width = 240;
    s.camera.height = 180;
    finalizeScene(s);
    ChannelImage o = runQuiet(s);
    for (const char* t : {"planar", "shadow-texture"}) {
        ChannelImage r = raster(s, t, {});
        for (const Light& l : s.lights) {
            const std::vector<float> onSmall = shadowValuesOn(o, r, l.name, 2.0f);
            size_t missed = 0;
            for (float v : onSmall) missed += v > 0.5f;
            const Comparison c = compare(o, r, l.name, 1);
            std::printf(
                "[ off-receiver ] %-14s %-4s: %zu of %zu shadowed pixels of the small box "
                "lit; %zu false shadow\n",
                t, l.name.c_str(), missed, onSmall.size(), c.falseShadow);
            ASSERT_GT(onSmall.size(), 100u) << l.name;
            EXPECT_EQ(missed, onSmall.size()) << t << " " << l.name;
            // The comparison counts them as false lit (away from boundaries).
            EXPECT_GE(c.falseLit, missed / 2) << t << " " << l.name;
            // The planar shadow clips what lies below the plane; a shadow texture has no depth,
            // so the buried box shades the floor through it (measured, docs/techniques.md).
            if (std::string(t) == "planar")
                EXPECT_LE(double(c.falseShadow), 0.001 * double(c.counted)) << l.name;
            else
                EXPECT_GT(c.falseShadow, 100u) << l.name;
        }
    }
}

// ---- soft shadows (issue 14) -------------------------------------------------------------------

// PCSS on the shipped penumbra_square (a rect light over a parallel square, where its similar
// triangles hold): a penumbra error well below a fixed PCF's; and with the light shrunk to a
// point-like 2 mm rect, the hard answer (agreement with the oracle as slope-bias has it).
TEST(Raster, PcssWidensThePenumbraAndHardensForAPointLikeLight) {
    REQUIRE_GL();
    Scene s = loadShipped("penumbra_square", 240, 180);
    ChannelImage o = runQuiet(s);
    const LightMetrics pcss = computeLightMetrics(o, raster(s, "pcss", {}), "panel", {});
    const LightMetrics pcf = computeLightMetrics(o, raster(s, "pcf", {"kernel=5"}), "panel", {});
    ASSERT_TRUE(pcss.penumbraMae && pcf.penumbraMae);
    std::printf("[ pcss ] penumbra_square penumbra mae: pcss %.4f, pcf 5x5 %.4f\n",
                *pcss.penumbraMae, *pcf.penumbraMae);
    EXPECT_LT(*pcss.penumbraMae, 0.5 * *pcf.penumbraMae);
    Scene tiny = s;
    tiny.lights[0].wsU *= 0.002 / glm::length(tiny.lights[0].wsU);
    tiny.lights[0].wsV *= 0.002 / glm::length(tiny.lights[0].wsV);
    finalizeScene(tiny);
    ChannelImage ot = runQuiet(tiny);
    Comparison soft = compare(ot, raster(tiny, "pcss", {}), "panel", 2);
    Comparison hard = compare(ot, raster(tiny, "slope-bias", {}), "panel", 2);
    Comparison rotated = compare(ot, raster(tiny, "pcss", {"pattern=1"}), "panel", 2);
    std::printf("[ pcss ] 2 mm light: agreement pcss %.5f, slope-bias %.5f of %zu\n",
                soft.agreement(), hard.agreement(), soft.counted);
    ASSERT_GT(soft.oracleShadow, 1000u);
    EXPECT_GE(soft.agreement(), hard.agreement() - 0.001);
    EXPECT_GE(soft.agreement(), 0.99);
    EXPECT_GE(rotated.agreement(), 0.99) << "the per-pixel turned pattern hardens too";
}

// The calibration of the soft-shadow comparison: accumulated hard shadows (exact per sample, with
// volumes) weighted as the oracle weights its samples converge to the oracle's V on the
// closed-form scene (a rect light over a parallel occluder): the mean penumbra error falls as the
// samples grow, and at 256 samples it lies within the oracle's 95% interval on >= 95% of the
// penumbra pixels.
TEST(Raster, AccumulationConvergesToTheOracle) {
    REQUIRE_GL();
    Scene s = loadShipped("penumbra_square", 200, 150);
    OracleOptions sampled;
    sampled.penumbra.method = PenumbraMethod::Sampled;  // its 95% intervals are the yardstick
    ChannelImage o = runOracle(s, sampled).image;
    const float* Vo = o.channel("panel.V");
    const float* SE = o.channel("panel.stderr");
    double previous = 1.0;
    for (int n : {1, 4, 16, 64, 256}) {
        ChannelImage r = raster(s, "accumulate", {"samples=" + std::to_string(n)});
        const float* Vr = r.channel("panel.V");
        size_t pen = 0, inside = 0;
        double sum = 0.0;
        for (size_t i = 0; i < o.pixelCount(); ++i) {
            if (!(Vo[i] > 0.0f && Vo[i] < 1.0f) ||
                o.channel(ch::kMeshId)[i] != r.channel(ch::kMeshId)[i])
                continue;
            ++pen;
            const double e = std::fabs(double(Vr[i]) - double(Vo[i]));
            sum += e;
            inside += e <= ch::kStdErrQuantile95 * double(SE[i]);
        }
        ASSERT_GT(pen, 1000u);
        const double mean = sum / double(pen), coverage = double(inside) / double(pen);
        std::printf(
            "[ accumulate ] %3d samples: penumbra mean |V - oracle| %.5f, within the "
            "oracle's interval %.4f of %zu\n",
            n, mean, coverage, pen);
        EXPECT_LT(mean, previous) << n;
        previous = mean;
        if (n == 256) {
            // As often as a 95% interval holds the truth, within binomial noise: fewer than
            // 0.95 n - 3.09 sd inside has probability below 1e-3 (one-sided).
            const double sd = std::sqrt(double(pen) * 0.95 * 0.05);
            EXPECT_GE(double(inside), 0.95 * double(pen) - 3.09 * sd) << coverage;
        }
    }
}

// The screen-space blur: radius 0 is its input, the hard shadow map, to the bit; a radius widens
// the hard edge towards the oracle's penumbra on penumbra_square.
TEST(Raster, BlurRadiusZeroIsItsInputAndARadiusSoftens) {
    REQUIRE_GL();
    Scene s = loadShipped("penumbra_square", 200, 150);
    const ChannelImage hard = raster(s, "slope-bias", {"resolution=1024"});
    const ChannelImage none = raster(s, "blur", {"radius=0", "resolution=1024"});
    EXPECT_EQ(0, std::memcmp(hard.channel("panel.V"), none.channel("panel.V"),
                             hard.pixelCount() * sizeof(float)));
    ChannelImage o = runQuiet(s);
    const LightMetrics h = computeLightMetrics(o, hard, "panel", {});
    const LightMetrics b =
        computeLightMetrics(o, raster(s, "blur", {"radius=12", "resolution=1024"}), "panel", {});
    ASSERT_TRUE(h.penumbraWidth && b.penumbraWidth && h.penumbraBias && b.penumbraBias);
    std::printf(
        "[ blur ] penumbra width error %.2f px hard, %.2f px blurred (radius 12); bias "
        "%.3f, %.3f\n",
        h.penumbraWidth->mean, b.penumbraWidth->mean, *h.penumbraBias, *b.penumbraBias);
    EXPECT_LT(b.penumbraWidth->mean, 0.8 * h.penumbraWidth->mean);
    EXPECT_GT(*b.penumbraBias, *h.penumbraBias) << "softer";
}

// Plane shifting softens the planar shadow's edge towards the oracle's penumbra on
// penumbra_square (a square 1.5 above the floor): narrower width error and a less hard bias than
// one projection, with the umbra still dark.
TEST(Raster, PlaneShiftSoftensThePlanarShadow) {
    REQUIRE_GL();
    Scene s = loadShipped("penumbra_square", 200, 150);
    ChannelImage o = runQuiet(s);
    const LightMetrics one = computeLightMetrics(o, raster(s, "planar", {}), "panel", {});
    const LightMetrics shifted = computeLightMetrics(o, raster(s, "plane-shift", {}), "panel", {});
    ASSERT_TRUE(one.penumbraWidth && shifted.penumbraWidth && one.penumbraBias &&
                shifted.penumbraBias && shifted.umbraMae);
    std::printf(
        "[ plane-shift ] width error %.2f px planar, %.2f shifted; bias %.3f, %.3f; "
        "umbra mae %.4f\n",
        one.penumbraWidth->mean, shifted.penumbraWidth->mean, *one.penumbraBias,
        *shifted.penumbraBias, *shifted.umbraMae);
    EXPECT_LT(shifted.penumbraWidth->mean, 0.75 * one.penumbraWidth->mean);
    EXPECT_GT(*shifted.penumbraBias, *one.penumbraBias);
    EXPECT_LT(*shifted.umbraMae, 0.02);
}

// The mean 10%-90% width, in pixels, of an image's own transitions on the floor (mesh 0) where
// the light faces it: penumbraWidthError's measure of the oracle, applied to one image.
double ownPenumbraWidth(const ChannelImage& img, const std::string& light) {
    const float* mesh = img.channel(ch::kMeshId);
    std::vector<uint8_t> floor(img.pixelCount());
    for (size_t i = 0; i < img.pixelCount(); ++i) floor[i] = mesh[i] == 0.0f;
    const float* V = img.channel(ch::lightChannel(light, ch::kVisibility));
    const auto w = penumbraWidthError(img.width(), img.height(), V, V, floor);
    return w ? w->oracleMeanWidth : 0.0;
}

// Plateaus widen the projected hard edge by the similar-triangles penumbra of each silhouette
// point's height: raising the square on penumbra_square from 0.75 to 2 (light at 4) widens its
// soft edge as the oracle's widens, within a factor 1.5 of the oracle's growth.
TEST(Raster, PlateausWidenWithTheOccludersHeight) {
    REQUIRE_GL();
    double oracle[2], plateaus[2];
    for (int k = 0; k < 2; ++k) {
        Scene s = loadShipped("penumbra_square", 240, 180);
        for (glm::dvec3& p : s.meshes[1].wsPositions) p.y = k == 0 ? 0.75 : 2.0;
        finalizeScene(s);
        const ChannelImage o = runQuiet(s), r = raster(s, "plateaus", {});
        oracle[k] = ownPenumbraWidth(o, "panel");
        plateaus[k] = ownPenumbraWidth(r, "panel");
        std::printf("[ plateaus ] square at %.2f: 10%%-90%% width %.2f px, oracle %.2f px\n",
                    k == 0 ? 0.75 : 2.0, plateaus[k], oracle[k]);
        ASSERT_GT(plateaus[k], 0.5) << "no soft edge at all";
    }
    const double growth = plateaus[1] / plateaus[0], oracleGrowth = oracle[1] / oracle[0];
    EXPECT_GT(growth, 1.5);
    EXPECT_LT(std::fabs(std::log(growth / oracleGrowth)), std::log(1.5))
        << growth << " against the oracle's " << oracleGrowth;
}

}  // namespace
}  // namespace so::test
