// The per-frame cost of a sequence's oracle (issue 52, docs/benchmarks.md): a frame is posed
// (core/scene_pose.h, sceneAtTime) and traced like any scene, so its cost against a static trace
// of one pose is the posing plus whatever tracing a different pose costs.
//
//   bench_sequence_oracle [--size N] [--grid G] [--frames F] [--reps R]
//
// The bench scene (bench_scene.h: a terrain of 2 G^2 triangles and 16 spheres) under a sun, one
// sphere sliding 8 units along x over the sequence (a LINEAR translation, as a glTF clip makes it).
// Per repetition, interleaved: the F frames of the sequence, each sceneAtTime + runOracle, and F
// static traces of one pose (frame F / 2, posed once beforehand). Prints the medians per frame
// and their ratio. Not a test: it prints figures.
#include <cstdio>
#include <memory>
#include <vector>

#include <glm/geometric.hpp>

#include <CLI/CLI.hpp>

#include "bench_scene.h"
#include "bench_util.h"
#include "core/gltf_animation.h"
#include "core/lights/make_light.h"
#include "core/scene_pose.h"
#include "oracle/oracle.h"

using namespace so;
using namespace so::bench;

namespace {

// Mesh `m` of `scene` slides by `dx` along x over [0, seconds].
void slide(Scene& scene, size_t m, double dx, double seconds) {
    auto node = std::make_shared<AnimatedNode>();
    AnimationTrack track;
    track.property = AnimatedProperty::Translation;
    track.times = {0.0, seconds};
    track.values = {glm::dvec4(0.0), glm::dvec4(dx, 0.0, 0.0, 0.0)};
    node->tracks.push_back(track);
    auto animation = std::make_shared<MeshAnimation>();
    animation->chain.push_back(node);
    animation->lsPositions = scene.meshes[m].wsPositions;
    scene.meshes[m].animation = animation;
}

}  // namespace

int main(int argc, char** argv) {
    int size = 512, grid = 256, frames = 8, reps = 5;
    CLI::App app{"per-frame cost of a sequence's oracle against a static trace of one pose"};
    app.add_option("--size", size, "image side")->check(CLI::Range(16, 8192));
    app.add_option("--grid", grid, "terrain grid cells per side")->check(CLI::Range(8, 4096));
    app.add_option("--frames", frames, "frames of the sequence")->check(CLI::Range(2, 1000));
    app.add_option("--reps", reps, "repetitions (median reported)")->check(CLI::Range(1, 100));
    CLI11_PARSE(app, argc, argv);
    Scene scene = makeBenchScene(grid, size);
    scene.lights.push_back(directionalLight("sun", glm::normalize(glm::dvec3(0.5, -1, 0.3))));
    scene.sequence = Sequence{frames, 30.0, ""};
    slide(scene, 1, 8.0, sequenceTime(*scene.sequence, frames - 1));
    const Scene still = sceneAtTime(scene, sequenceTime(*scene.sequence, frames / 2));
    OracleOptions options;
    std::vector<double> sequenceSeconds, staticSeconds, poseSeconds;
    for (int r = 0; r < reps; ++r) {
        double pose = 0.0;
        sequenceSeconds.push_back(timeOnce([&] {
                                      for (int k = 0; k < frames; ++k) {
                                          Scene posed;
                                          pose += timeOnce([&] {
                                              posed = sceneAtTime(scene,
                                                                  sequenceTime(*scene.sequence, k));
                                          });
                                          runOracle(posed, options);
                                      }
                                  }) /
                                  frames);
        poseSeconds.push_back(pose / frames);
        staticSeconds.push_back(timeOnce([&] {
                                    for (int k = 0; k < frames; ++k) runOracle(still, options);
                                }) /
                                frames);
    }
    const double seq = median(sequenceSeconds), stat = median(staticSeconds);
    std::printf("%zu triangles, %dx%d, %d frames, %d reps%s\n", still.stats.triangles, size, size,
                frames, reps, cpuClock() ? " (processor time)" : "");
    std::printf("sequence frame %.4f s (posing %.4f s), static pose %.4f s: ratio %.3f\n", seq,
                median(poseSeconds), stat, seq / stat);
    return 0;
}
