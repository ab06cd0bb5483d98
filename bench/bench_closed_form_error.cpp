// The penumbra error of shadow-visibility images against Lambert's closed form
// (tests/support/lambert.cpp), for scripts/cycles-compare (docs/benchmarks.md, "cycles-compare"):
// any renderer's `LIGHT.V` (Cycles' shadows.exr, the oracle's oracle.exr) judged at the surface
// points of one G-buffer.
//
//   bench_closed_form_error SCENE --geometry GBUFFER.exr [--light NAME] IMAGE.exr...
//
// The scene must have the closed form: one rect light, horizontal, its edges along x and z,
// emitting downwards; flat horizontal meshes, all at one height (the receivers) but those at one
// greater height below the light, which together fill an axis-aligned rectangle (the occluder),
// as the shipped penumbra_square. The closed form is derived from the loaded scene, and a scene
// without it is one line and exit 2, so no number is ever judged against the wrong shadow.
//
// GBUFFER.exr: `shadow-oracle view`'s gbuffer.exr (or an oracle.exr) of the same size: A, P.*, N.*.
// Prints one JSON object: the penumbra (covered pixels with 0 < V_exact < 1) and, per image, the
// mean, 99th percentile and signed mean of V - V_exact there, and how many covered pixels outside
// it are off by more than 1e-3. `noise_bound_1spp` is the mean over the penumbra of
// sqrt(2/pi) sqrt(V (1 - V)): E|error| of one independent sample; N independent samples per pixel
// give it over sqrt(N) (the bound tests/cli/blender_test.cpp holds Cycles to).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <CLI/CLI.hpp>

#include "core/channels.h"
#include "core/error.h"
#include "core/image.h"
#include "core/scene.h"
#include "lambert.h"

using namespace so;

namespace {

[[noreturn]] void noClosedForm(const std::string& scenePath, const std::string& why) {
    throwInputError(scenePath, "", "has no closed form for cycles-compare: " + why);
}

test::AxisRect lightRect(const std::string& scenePath, const Scene& scene) {
    if (scene.lights.size() != 1 || std::string(lightTypeName(scene.lights[0].type)) != "rect")
        noClosedForm(scenePath, "it needs exactly one light, a rect");
    const Light& l = scene.lights[0];
    const bool alongX = l.wsU.y == 0 && l.wsU.z == 0 && l.wsU.x != 0;
    const bool alongZ = l.wsV.y == 0 && l.wsV.x == 0 && l.wsV.z != 0;
    if (!alongX || !alongZ || !(l.wsEmitNormal().y < 0))
        noClosedForm(scenePath,
                     "light " + l.name + ": u must lie along x, v along z, emitting downwards");
    const glm::dvec3 c = l.wsPosition;
    const double hu = std::fabs(l.wsU.x) / 2, hv = std::fabs(l.wsV.z) / 2;
    return {c.y, c.x - hu, c.x + hu, c.z - hv, c.z + hv};
}

// The occluder: the flat meshes above the receivers' height, which must fill their bounds.
test::AxisRect occluderRect(const std::string& scenePath, const Scene& scene, double lightY) {
    std::map<double, std::vector<const MeshPrimitive*>> byHeight;
    for (const MeshPrimitive& m : scene.meshes) {
        if (m.wsPositions.empty()) continue;
        const double y = m.wsPositions[0].y;
        for (const glm::dvec3& p : m.wsPositions)
            if (p.y != y) noClosedForm(scenePath, "mesh " + m.name + " is not horizontal");
        byHeight[y].push_back(&m);
    }
    if (byHeight.size() != 2)
        noClosedForm(scenePath, "its meshes must lie at two heights (receivers, one occluder)");
    const double y = byHeight.rbegin()->first;
    if (!(y < lightY)) noClosedForm(scenePath, "the occluder is not below the light");
    test::AxisRect r{y, INFINITY, -INFINITY, INFINITY, -INFINITY};
    double area = 0;
    for (const MeshPrimitive* m : byHeight.rbegin()->second) {
        for (const glm::dvec3& p : m->wsPositions) {
            r.x0 = std::min(r.x0, p.x), r.x1 = std::max(r.x1, p.x);
            r.z0 = std::min(r.z0, p.z), r.z1 = std::max(r.z1, p.z);
        }
        for (size_t t = 0; t < m->triangleCount(); ++t) {
            const glm::dvec3& a = m->wsPositions[m->indices[3 * t]];
            const glm::dvec3& b = m->wsPositions[m->indices[3 * t + 1]];
            const glm::dvec3& c = m->wsPositions[m->indices[3 * t + 2]];
            area += glm::length(glm::cross(b - a, c - a)) / 2;
        }
    }
    // Overlapping triangles would add up past the box; gaps would fall short of it.
    const double box = (r.x1 - r.x0) * (r.z1 - r.z0);
    if (!(std::fabs(area - box) <= 1e-9 * box))
        noClosedForm(scenePath, "the occluder's triangles do not fill their bounding rectangle");
    return r;
}

struct ImageError {
    double mae = 0, p99 = 0, signedMean = 0, outsideMax = 0;
    size_t outsideOff = 0;  // covered pixels outside the penumbra off by more than 1e-3
};

const float* channelOf(const ChannelImage& img, const std::string& path, const std::string& name) {
    if (!img.has(name)) throwInputError(path, name, "missing");
    return img.channel(name);
}

}  // namespace

int main(int argc, char** argv) try {
    std::string scenePath, geometryPath, lightName;
    std::vector<std::string> images;
    CLI::App app{"penumbra error of V images against the closed form (scripts/cycles-compare)"};
    app.add_option("scene", scenePath, "scene with the closed form (penumbra_square)")->required();
    app.add_option("--geometry", geometryPath, "gbuffer.exr of `view` (A, P, N)")->required();
    app.add_option("--light", lightName, "channel prefix (default: the scene's light's name)");
    app.add_option("images", images, "images with LIGHT.V, the geometry's size")->required();
    CLI11_PARSE(app, argc, argv);

    const Scene scene = loadScene(scenePath);
    const test::AxisRect light = lightRect(scenePath, scene);
    const test::AxisRect occluder = occluderRect(scenePath, scene, light.y);
    if (lightName.empty()) lightName = scene.lights[0].name;

    namespace ch = channels;
    const ChannelImage g = readExr(geometryPath);
    const float* A = channelOf(g, geometryPath, ch::kHit);
    const float* P[3] = {channelOf(g, geometryPath, ch::kPX), channelOf(g, geometryPath, ch::kPY),
                         channelOf(g, geometryPath, ch::kPZ)};
    const float* N[3] = {channelOf(g, geometryPath, ch::kNX), channelOf(g, geometryPath, ch::kNY),
                         channelOf(g, geometryPath, ch::kNZ)};
    std::vector<double> exact(g.pixelCount(), -1.0);  // -1: background
    size_t covered = 0, penumbra = 0;
    double noise1 = 0;
    for (size_t i = 0; i < g.pixelCount(); ++i) {
        if (A[i] == 0.0f) continue;
        ++covered;
        exact[i] = test::exactRectLightRectOccluderV({P[0][i], P[1][i], P[2][i]},
                                                     {N[0][i], N[1][i], N[2][i]}, light, occluder);
        if (exact[i] > 1e-9 && exact[i] < 1 - 1e-9) {
            ++penumbra;
            noise1 += std::sqrt(2 / M_PI) * std::sqrt(exact[i] * (1 - exact[i]));
        }
    }
    nlohmann::json out = {
        {"scene", scenePath},
        {"geometry", geometryPath},
        {"light", lightName},
        {"width", g.width()},
        {"height", g.height()},
        {"covered_pixels", covered},
        {"penumbra_pixels", penumbra},
        {"noise_bound_1spp", penumbra ? noise1 / double(penumbra) : 0.0},
        {"images", nlohmann::json::array()},
    };
    for (const std::string& path : images) {
        const ChannelImage img = readExr(path);
        if (img.width() != g.width() || img.height() != g.height())
            throwInputError(path, "size",
                            "not the geometry's " + std::to_string(g.width()) + "x" +
                                std::to_string(g.height()));
        const float* V = channelOf(img, path, lightName + "." + ch::kVisibility);
        ImageError e;
        std::vector<double> errors;
        for (size_t i = 0; i < g.pixelCount(); ++i) {
            if (exact[i] < 0) continue;
            const double d = double(V[i]) - exact[i];
            if (exact[i] > 1e-9 && exact[i] < 1 - 1e-9) {
                errors.push_back(std::fabs(d));
                e.mae += std::fabs(d);
                e.signedMean += d;
            } else {
                e.outsideMax = std::max(e.outsideMax, std::fabs(d));
                e.outsideOff += std::fabs(d) > 1e-3;
            }
        }
        if (!errors.empty()) {
            e.mae /= double(errors.size());
            e.signedMean /= double(errors.size());
            const size_t k = std::min(errors.size() - 1, size_t(0.99 * double(errors.size())));
            std::nth_element(errors.begin(), errors.begin() + std::ptrdiff_t(k), errors.end());
            e.p99 = errors[k];
        }
        out["images"].push_back({{"file", path},
                                 {"penumbra_mae", e.mae},
                                 {"penumbra_p99", e.p99},
                                 {"penumbra_signed_mean", e.signedMean},
                                 {"outside_max_error", e.outsideMax},
                                 {"outside_pixels_off", e.outsideOff}});
    }
    std::cout << out.dump(2) << "\n";
    return 0;
} catch (const std::exception& e) {  // InputError: "file: field: why"
    std::cerr << "error: " << e.what() << "\n";
    return 2;
}
