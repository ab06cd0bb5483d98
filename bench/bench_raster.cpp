// Per technique and shadow-map resolution, the raster path's timed passes on a shipped scene, each
// as a ratio to `basic` at the same resolution (docs/benchmarks.md).
//
//   bench_raster [--scene scenes/spot_objects.scene.json] [--frames 5] [--width 640 --height 480]
//
// On llvmpipe the GL timer queries measure CPU work; absolute times mean something on a GPU only,
// the ratios on both. Prints a note and exits 0 where no OpenGL context can be had.
#include <cstdio>
#include <map>
#include <string>

#include <CLI/CLI.hpp>

#include "core/scene.h"
#include "raster_compare/gl/gl_context.h"
#include "raster_compare/gl/renderer.h"
#include "raster_compare/gl/technique.h"

using namespace so;

int main(int argc, char** argv) {
    std::string scenePath = SO_SCENES_DIR "/spot_objects.scene.json";
    RasterOptions options;
    options.width = 640;
    options.height = 480;
    CLI::App app{"raster-path timings per technique and resolution, as ratios to basic"};
    app.add_option("--scene", scenePath, "scene file");
    app.add_option("--frames", options.frames, "timed frames (median reported)")
        ->check(CLI::Range(1, 1000));
    app.add_option("--width", options.width, "image width")->check(CLI::Range(16, 8192));
    app.add_option("--height", options.height, "image height")->check(CLI::Range(16, 8192));
    CLI11_PARSE(app, argc, argv);
    std::unique_ptr<GlContext> gl;
    try {
        gl = std::make_unique<GlContext>();
    } catch (const GlUnavailable& e) {
        std::printf("no OpenGL 4.5 through EGL (%s): nothing to measure\n", e.what());
        return 0;
    }
    const Scene scene = loadScene(scenePath);
    std::printf("%s, %dx%d, %zu lights, %s | %s, median of %d frames\n", scenePath.c_str(),
                options.width, options.height, scene.lights.size(), gl->renderer().c_str(),
                gl->version().c_str(), options.frames);
    std::printf("%-15s %5s %11s %11s %9s %9s   %s\n", "technique", "res", "shadow ms", "visib. ms",
                "camera ms", "wall ms", "ratios to basic (shadow, visibility, wall)");
    for (int res : {1024, 2048, 4096}) {
        std::map<std::string, double> basicMs;
        // basic first: it is the baseline of the ratios.
        std::vector<std::string> names = {"basic"};
        for (const TechniqueInfo* t : allTechniques())
            if (t->name != "basic") names.push_back(t->name);
        for (const std::string& name : names) {
            const std::unique_ptr<Technique> t =
                createTechnique(name, {"resolution=" + std::to_string(res)});
            const RasterResult r = renderRaster(scene, *t, options, *gl);
            double shadow = 0, vis = 0;
            for (const RasterLightStats& l : r.stats.lights)
                for (const auto& [pass, ms] : l.passMs) (pass == "visibility" ? vis : shadow) += ms;
            const double cam = r.stats.timings.cameraMs, wall = r.stats.timings.wallMs;
            if (name == "basic") basicMs = {{"shadow", shadow}, {"vis", vis}, {"wall", wall}};
            std::printf("%-15s %5d %11.2f %11.2f %9.2f %9.2f   %.2f %.2f %.2f\n", name.c_str(), res,
                        shadow, vis, cam, wall, shadow / basicMs["shadow"], vis / basicMs["vis"],
                        wall / basicMs["wall"]);
        }
    }
    return 0;
}
