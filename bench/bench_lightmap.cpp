// The lightmap's artifacts that need the image itself, on shipped scenes (docs/benchmarks.md,
// "Lightmaps", written by scripts/lightmap-table with the sweep scenes/sweeps/lightmap.json, which
// gives the errors against the oracle): per scene, light, density and filter,
//   - the filtered edge's width: the mean 10%-90% width of the image's own transitions where the
//     light faces the surface, in pixels, beside a texel's size in pixels there (the median of
//     NAME.aliasing_pred), for hard lights (an area light's penumbra is the sweep's
//     penumbra_width_error_px);
//   - the seams: the share of those pixels whose V moves by more than 0.02 when the charts are not
//     dilated (dilate=0 against the default), and the largest move;
//   - frame and bake times and memory, against the baseline of the same run: slope-bias at the
//     bake's resolution, the very shadow map a bake is made from, rendered every frame instead.
// Every technique of a scene takes turns frame by frame (renderInterleaved). No oracle.
//
//   bench_lightmap [--scene FILE]... [--densities 4,8,16,32,48] [--width 320 --height 240]
//                  [--frames 3] [--json FILE]
//
// Prints a note and exits 0 where no OpenGL context can be had.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "core/channels.h"
#include "core/lights/light_kind.h"
#include "core/scene.h"
#include "raster_compare/compare/penumbra_width.h"
#include "raster_compare/gl/context/gl_context.h"
#include "raster_compare/gl/render/renderer.h"
#include "raster_compare/gl/technique.h"

using namespace so;
namespace ch = channels;

namespace {

// The pixels where the light faces the surface the camera sees (and a spot's cone holds it):
// where a transition of V is a shadow's edge, not the facing convention's.
std::vector<uint8_t> facingPixels(const ChannelImage& img, const Light& light) {
    std::vector<uint8_t> mask(img.pixelCount(), 0);
    const float *A = img.channel(ch::kHit), *px = img.channel(ch::kPX), *py = img.channel(ch::kPY),
                *pz = img.channel(ch::kPZ), *nx = img.channel(ch::kNX), *ny = img.channel(ch::kNY),
                *nz = img.channel(ch::kNZ);
    const double cosOuter = std::cos(light.outerConeDeg * 3.14159265358979323846 / 180.0);
    for (size_t i = 0; i < img.pixelCount(); ++i) {
        if (A[i] == 0.0f) continue;
        const glm::dvec3 p(px[i], py[i], pz[i]), n(nx[i], ny[i], nz[i]);
        const glm::dvec3 l = isDirectional(light) ? -glm::normalize(light.wsDirection)
                                                  : glm::normalize(light.wsPosition - p);
        bool lit = glm::dot(n, l) > 0.0;
        if (hasCone(light))
            lit = lit && glm::dot(-l, glm::normalize(light.wsDirection)) >= cosOuter;
        mask[i] = lit;
    }
    return mask;
}

struct Measured {
    std::string label;
    double edgePx = 0.0, texelPx = 0.0;
    size_t profiles = 0;
};

// The image's own mean 10%-90% edge width (penumbraWidthError's measure of one image) and the
// median texel footprint in pixels over the mask.
Measured edgeWidth(const ChannelImage& img, const std::string& light,
                   const std::vector<uint8_t>& mask) {
    Measured m;
    const float* V = img.channel(ch::lightChannel(light, ch::kVisibility));
    const auto w = penumbraWidthError(img.width(), img.height(), V, V, mask);
    if (w) m.edgePx = w->oracleMeanWidth, m.profiles = w->profiles;
    const float* pred = img.channel(ch::lightChannel(light, ch::kPredictedAliasing));
    std::vector<float> ratios;
    for (size_t i = 0; i < img.pixelCount(); ++i)
        if (mask[i] && pred[i] > 0.0f) ratios.push_back(pred[i]);
    if (!ratios.empty()) {
        std::nth_element(ratios.begin(), ratios.begin() + long(ratios.size() / 2), ratios.end());
        // aliasing_pred is a texel's size over a pixel's: a texel spans that many pixels.
        m.texelPx = ratios[ratios.size() / 2];
    }
    return m;
}

struct Setting {
    std::string label;
    double density = 0.0;
    std::string filter;
    int dilate = 2;
};

nlohmann::json measureScene(const std::string& path, const std::vector<double>& densities,
                            const RasterOptions& options, const GlContext& gl) {
    const Scene scene = loadScene(path);
    std::vector<Setting> settings;
    std::vector<std::unique_ptr<Technique>> owned;
    for (double d : densities) {
        char ds[32];
        std::snprintf(ds, sizeof ds, "%g", d);
        for (const char* f : {"nearest", "bilinear", "bicubic"})
            settings.push_back(
                {std::string("lightmap:texels_per_unit=") + ds + ",filter=" + f, d, f, 2});
        settings.push_back(
            {std::string("lightmap:texels_per_unit=") + ds + ",filter=bilinear,dilate=0", d,
             "bilinear", 0});
    }
    std::vector<const Technique*> techniques;
    for (const Setting& s : settings) {
        char ds[32];
        std::snprintf(ds, sizeof ds, "%g", s.density);
        owned.push_back(
            createTechnique("lightmap", {std::string("texels_per_unit=") + ds, "filter=" + s.filter,
                                         "dilate=" + std::to_string(s.dilate)}));
        techniques.push_back(owned.back().get());
    }
    // The baseline: the shadow map a bake is made from, every frame.
    owned.push_back(createTechnique("slope-bias", {"resolution=2048"}));
    techniques.push_back(owned.back().get());
    std::vector<RasterResult> results(techniques.size());
    renderInterleaved(scene, techniques, options, gl,
                      {nullptr, [&](size_t i, RasterResult&& r) { results[i] = std::move(r); }});
    nlohmann::json rows = nlohmann::json::array();
    for (size_t li = 0; li < scene.lights.size(); ++li) {
        const Light& light = scene.lights[li];
        const bool hard = !isAreaLight(light.type) || !scene.hasEffect("penumbra");
        const std::vector<uint8_t> mask = facingPixels(results.back().image, light);
        for (size_t i = 0; i < techniques.size(); ++i) {
            const RasterResult& r = results[i];
            const RasterLightStats& ls = r.stats.lights[li];
            nlohmann::json row = {{"light", light.name},
                                  {"hard", hard},
                                  {"frame_ms", r.stats.timings.wallMs.median},
                                  {"memory_bytes", ls.memoryBytes}};
            if (i + 1 == techniques.size()) {
                row["label"] = "slope-bias:resolution=2048";
            } else {
                const Setting& s = settings[i];
                row.update({{"label", s.label},
                            {"texels_per_unit", s.density},
                            {"filter", s.filter},
                            {"dilate", s.dilate},
                            {"bake_ms", ls.bakeMs.value_or(0.0)}});
            }
            if (hard) {
                const Measured m = edgeWidth(r.image, light.name, mask);
                row.update(
                    {{"edge_px", m.edgePx}, {"texel_px", m.texelPx}, {"profiles", m.profiles}});
            }
            // Seams: this bilinear setting without dilation against the same one with it.
            if (i + 1 < techniques.size() && settings[i].dilate == 0) {
                const std::string name = ch::lightChannel(light.name, ch::kVisibility);
                const float *bare = r.image.channel(name),
                            *dilated = results[i - 2].image.channel(name);
                size_t counted = 0, moved = 0;
                double largest = 0.0;
                for (size_t p = 0; p < r.image.pixelCount(); ++p) {
                    if (!mask[p]) continue;
                    ++counted;
                    const double d = std::fabs(double(bare[p]) - double(dilated[p]));
                    moved += d > 0.02;
                    largest = std::max(largest, d);
                }
                row.update({{"seam_share", counted ? double(moved) / double(counted) : 0.0},
                            {"seam_max", largest}});
            }
            rows.push_back(row);
        }
    }
    return {{"scene", path},
            {"width", results.front().stats.width},
            {"height", results.front().stats.height},
            {"rows", rows}};
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> scenes = {SO_SCENES_DIR "/contact_box.scene.json",
                                       SO_SCENES_DIR "/soft_chair.scene.json",
                                       SO_SCENES_DIR "/terrain_sun.scene.json"};
    std::vector<double> densities = {4, 8, 16, 32, 48};
    std::string jsonPath;
    RasterOptions options;
    options.width = 320;
    options.height = 240;
    options.frames = 3;
    CLI::App app{"the lightmap's edge widths, seams, frame and bake times against slope-bias"};
    app.add_option("--scene", scenes, "scene files (default: the three shipped ones)");
    app.add_option("--densities", densities, "texels per unit")->delimiter(',');
    app.add_option("--width", options.width, "image width")->check(CLI::Range(16, 8192));
    app.add_option("--height", options.height, "image height")->check(CLI::Range(16, 8192));
    app.add_option("--frames", options.frames, "timed frames")->check(CLI::Range(1, 1000));
    app.add_option("--json", jsonPath, "write the measurements here as JSON");
    CLI11_PARSE(app, argc, argv);
    std::unique_ptr<GlContext> gl;
    try {
        gl = std::make_unique<GlContext>();
    } catch (const GlUnavailable& e) {
        std::printf("no OpenGL 4.5 through EGL (%s): nothing to measure\n", e.what());
        return 0;
    }
    nlohmann::json out = {{"gl", gl->renderer() + " | " + gl->version()},
                          {"frames", options.frames},
                          {"scenes", nlohmann::json::array()}};
    for (const std::string& s : scenes) {
        out["scenes"].push_back(measureScene(s, densities, options, *gl));
        for (const nlohmann::json& row : out["scenes"].back()["rows"])
            std::printf(
                "%-40s %-8s frame %7.2f ms  bake %8.1f ms  edge %5.2f px (texel %5.2f px)"
                "  seams %.4f\n",
                row["label"].get<std::string>().c_str(), row["light"].get<std::string>().c_str(),
                row["frame_ms"].get<double>(), row.value("bake_ms", 0.0), row.value("edge_px", 0.0),
                row.value("texel_px", 0.0), row.value("seam_share", 0.0));
    }
    if (!jsonPath.empty()) std::ofstream(jsonPath) << out.dump(1) << "\n";
    return 0;
}
