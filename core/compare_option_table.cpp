#include "core/compare_option_table.h"

#include <vector>

namespace so {

namespace {

// The rows, in the order of docs/cli.md. A default is stated once, by the constant a row uses.
std::vector<OptionSpec> makeTable() {
    std::vector<OptionSpec> t;
    t.push_back(integerOption(
        "boundary_radius", kDefaultBoundaryRadius, 0, 64,
        kSurfaceCompare | kSurfaceSweep | kSurfaceApi, "r of docs/metrics.md",
        "r of [metrics.md](metrics.md): the pixels within r of an oracle shadow boundary are the "
        "boundary band of the `boundary_*` metrics"));
    t.push_back(zeroMeans(
        integerOption("frames_path", 0, 2, 10000, kSurfaceCompare,
                      "also render N frames along the scene's camera_path (oracle and every "
                      "technique) for temporal_flicker_rate (docs/metrics.md)",
                      "also render N frames along the scene's `camera_path` (scene_format 2), the "
                      "oracle and every technique once per frame, for `temporal_flicker_rate` "
                      "([metrics.md](metrics.md)); techniques only, not `--image`"),
        "0 (off)"));
    t.back().excludes = {"sequence", "converge"};
    t.push_back(flagOption(
        "sequence", kSurfaceCompare | kSurfaceSweep,
        "judge the scene's sequence frame by frame: every technique over its frames, each against "
        "that frame's oracle, history kept (docs/metrics.md#sequence)",
        "judge the scene's `sequence` (scene_format 5) frame by frame: the oracle of every frame "
        "(cached per frame), every technique rendered over the frames in order, keeping its "
        "history, for metrics.json's `sequence` ([metrics.md](metrics.md#sequence)); the row's "
        "other metrics describe the last frame; techniques only, not `--image`; in a sweep spec "
        "`true` or "
        "`false`"));
    t.back().excludes = {"frames_path", "converge"};
    t.push_back(zeroMeans(
        integerOption(
            "converge", 0, 1, kMaxConvergeFrames, kSurfaceCompare | kSurfaceSweep | kSurfaceRaster,
            "render N still frames, the frame index turning, and judge the last: a technique that "
            "builds over frames converged, not cold (history_frames, docs/metrics.md)",
            "render N still frames of the scene (nothing moves; the frame index runs 0 to N - 1, "
            "so jittered taps turn and histories fill) and judge the last: a technique that builds "
            "over frames graded converged instead of cold (metrics.json's `history_frames` says "
            "which, [metrics.md](metrics.md#history-frames)); 1 is the single frame; the still "
            "frames' flicker and error per frame are metrics.json's `sequence`; techniques only, "
            "not `--image`"),
        "0 (one frame)"));
    t.back().excludes = {"sequence", "frames_path"};
    return t;
}

}  // namespace

const OptionTable& compareOptionTable() {
    static const std::vector<OptionSpec> rows = makeTable();
    static const OptionTable table{"compare option", rows};
    return table;
}

const OptionSpec& compareOption(const std::string& key) {
    return compareOptionTable().at(key);
}

}  // namespace so
