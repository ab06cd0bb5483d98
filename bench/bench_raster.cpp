// Per technique and shadow-map resolution, the raster path's timed passes on a shipped scene, each
// as a ratio to `basic` at the same resolution (docs/benchmarks.md).
//
//   bench_raster [--scene scenes/spot_objects.scene.json] [--frames 9] [--width 640 --height 480]
//                [--resolution R ...] [--work on|off]
//
// --work off renders without the counted frame (docs/metrics.md, Work); the last line of each
// resolution gives the whole render's seconds (set-ups, counted frames, warm-up and timed
// frames), so two runs show what counting adds to a run, and the timed passes that it adds none.
//
// On llvmpipe the GL timer queries measure CPU work; absolute times mean something on a GPU only,
// the ratios on both. Prints a note and exits 0 where no OpenGL context can be had.
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/scene.h"
#include "raster_compare/gl/context/gl_context.h"
#include "raster_compare/gl/render/renderer.h"
#include "raster_compare/gl/technique.h"

using namespace so;

int main(int argc, char** argv) {
    std::string scenePath = SO_SCENES_DIR "/spot_objects.scene.json";
    RasterOptions options;
    options.width = 640;
    options.height = 480;
    CLI::App app{"raster-path timings per technique and resolution, as ratios to basic"};
    app.add_option("--scene", scenePath, "scene file");
    app.add_option("--frames", options.frames, "timed frames (median and quartiles reported)")
        ->check(CLI::Range(1, 1000));
    app.add_option("--width", options.width, "image width")->check(CLI::Range(16, 8192));
    app.add_option("--height", options.height, "image height")->check(CLI::Range(16, 8192));
    std::vector<int> resolutions = {1024, 2048, 4096};
    app.add_option("--resolution", resolutions, "shadow-map resolutions")
        ->check(CLI::Range(16, 16384));
    std::string work = "on";
    app.add_option("--work", work, "count the work in a frame of its own first")
        ->check(CLI::IsMember({"on", "off"}));
    CLI11_PARSE(app, argc, argv);
    std::unique_ptr<GlContext> gl;
    try {
        gl = std::make_unique<GlContext>();
    } catch (const GlUnavailable& e) {
        std::printf("no OpenGL 4.5 through EGL (%s): nothing to measure\n", e.what());
        return 0;
    }
    const Scene scene = loadScene(scenePath);
    std::printf(
        "%s, %dx%d, %zu lights, %s | %s, median of %d frames (p25-p75 of the shadow pass), "
        "techniques interleaved frame by frame\n",
        scenePath.c_str(), options.width, options.height, scene.lights.size(),
        gl->renderer().c_str(), gl->version().c_str(), options.frames);
    std::printf("%-15s %5s %19s %11s %9s %9s   %s\n", "technique", "res", "shadow ms (p25-p75)",
                "visib. ms", "camera ms", "wall ms", "ratios to basic (shadow, visibility, wall)");
    options.countWork = work == "on";
    for (int res : resolutions) {
        // basic first: it is the baseline of the ratios.
        std::vector<std::string> names = {"basic"};
        for (const TechniqueInfo* t : allTechniques())
            if (t->name != "basic") names.push_back(t->name);
        std::vector<std::unique_ptr<Technique>> owned;
        std::vector<const Technique*> techniques;
        for (const std::string& name : names) {
            // Families without a map (shadow volumes) render alike at every resolution: the
            // same technique each time, beside the maps of that resolution.
            std::vector<std::string> settings;
            for (const ParamSpec& p : findTechnique(name).params)
                if (p.name == "resolution") settings.push_back("resolution=" + std::to_string(res));
            owned.push_back(createTechnique(name, settings));
            techniques.push_back(owned.back().get());
        }
        std::map<std::string, double> basicMs;
        const auto t0 = std::chrono::steady_clock::now();
        renderInterleaved(
            scene, techniques, options, *gl,
            {nullptr, [&](size_t i, RasterResult&& r) {
                 TimingStats shadow, vis;
                 for (const RasterLightStats& l : r.stats.lights)
                     for (const auto& [pass, t] : l.passMs)
                         (pass == "visibility" ? vis : shadow) += t;
                 const double cam = r.stats.timings.cameraMs.median,
                              wall = r.stats.timings.wallMs.median;
                 if (i == 0)
                     basicMs = {{"shadow", shadow.median}, {"vis", vis.median}, {"wall", wall}};
                 std::printf(
                     "%-15s %5d %7.2f (%5.2f-%5.2f) %11.2f %9.2f %9.2f   %.2f %.2f "
                     "%.2f\n",
                     names[i].c_str(), res, shadow.median, shadow.p25, shadow.p75, vis.median, cam,
                     wall, shadow.median / basicMs["shadow"], vis.median / basicMs["vis"],
                     wall / basicMs["wall"]);
             }});
        std::printf("whole render at %d, work %s: %.2f s\n", res, work.c_str(),
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    return 0;
}
