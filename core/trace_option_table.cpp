#include "core/trace_option_table.h"

#include <string>
#include <vector>

namespace so {

namespace {

constexpr unsigned kAll = kSurfaceTrace | kSurfaceCompare | kSurfaceSweep | kSurfaceApi;
constexpr double kMaxSamples = 1 << 20;

constexpr unsigned kCli = kSurfaceTrace | kSurfaceCompare;
constexpr unsigned kNoCompare = kSurfaceTrace | kSurfaceSweep | kSurfaceApi;

// The rows, in the order of docs/cli.md. A default is stated once, here; a change of one is a
// change of this line (and of the API's and Python's spelling of it, which the tests compare).
// Every row changes the oracle's result, so is in its cache key, unless it says sameResult.
std::vector<OptionSpec> makeTable() {
    std::vector<OptionSpec> t;
    t.push_back(zeroMeans(integerOption("width", 0, 1, kMaxImageSide, kAll, "image width",
                                        "image width; the field of view stays vertical"),
                          "the scene camera's"));
    t.push_back(zeroMeans(
        integerOption("height", 0, 1, kMaxImageSide, kAll, "image height", "image height"),
        "the scene camera's"));
    t.push_back(sameResult(
        zeroMeans(integerOption("threads", 0, 1, 1024, kCli | kSurfaceApi, "worker threads",
                                "threads for tracing; the output is bit-identical for any N"),
                  "all cores")));
    t.push_back(
        integerOption("seed", 0, 0, 4294967295.0, kAll, "seed of the area-light sample sequences",
                      "seed of the area-light sample sequences; the output is a function of "
                      "the scene, the options and the seed only"));
    t.push_back(
        realOption("target_error", 0.01, 1e-4, 0.5, kAll,
                   "area lights: stop a pixel when its 95% half-width is below this",
                   "area lights (`penumbra`): a pixel stops sampling when the half-width of its "
                   "95% interval is at most E"));
    t.push_back(
        realOption("agreement_target", 0.01, 1e-4, 0.5, kAll,
                   "area lights: a pixel whose samples all agree (lit, or umbra) stops at the "
                   "larger of this and --target-error (docs/oracle.md)",
                   "area lights: a pixel whose samples all agree (all lit, or all shadowed) "
                   "stops when its half-width, which only the prior sets there, is at most the "
                   "larger of A and E ([oracle.md](oracle.md), stopping rule)"));
    t.push_back(integerOption("max_spp", kDefaultMaxSpp, 16, kMaxSamples, kNoCompare,
                              "area lights: most samples per pixel",
                              "area lights: the most samples a pixel may take"));
    t.push_back(zeroMeans(
        integerOption(
            "spp", 0, 1, kMaxSamples, kNoCompare,
            "area lights: exactly this many samples per pixel (no adaptivity)",
            "area lights: exactly N samples per pixel instead, rounded up to a multiple of 16"),
        "adaptive"));
    t.back().excludes = {"target_error", "agreement_target", "max_spp"};
    t.push_back(
        integerOption("verify", 0, 0, kMaxSamples, kCli | kSurfaceApi,
                      "re-trace N random pixels per light (plus up to N near the horizon) with "
                      "an independent exact tracer; exit 3 on any disagreement",
                      "re-trace N random pixels per light, plus up to N whose light is within 3 "
                      "degrees of the horizon, with an independent exact tracer "
                      "([oracle.md](oracle.md#verification)); prints a summary line; exit 3 on "
                      "any disagreement. Part of the cache key (`compare`)"));
    t.back().defaultText = "0 (off)";
    t.push_back(integerOption("verify_samples", 4096, 64, kMaxSamples, kSurfaceTrace,
                              "reference samples per area-light pixel checked",
                              "reference samples per checked pixel of a sampled area light"));
    t.push_back(nameOption(
        "penumbra", "auto", {"sampled", "exact", "both", "auto"}, kAll,
        "auto (per light, exact or sampled, whichever a probe estimates cheaper), sampled (RQMC "
        "with 95% intervals), exact (rect and polygon lights: clipped polygons on every pixel, "
        "stderr 0 there; disk and sphere lights: with a stated error, NAME.bound) or both "
        "(V sampled, V_exact beside it)",
        "area lights with the `penumbra` effect: `auto` (per light, `exact` or `sampled`, "
        "whichever a probe of one pixel in 64 estimates cheaper at the requested target, exact "
        "unless its estimate is over 1.5 times sampling's; oracle.json's `penumbra_choice` says "
        "which and why), `sampled` (RQMC with 95% intervals), `exact` (every pixel without "
        "sampling, stderr 0, `NAME.exact` 1: rect and polygon lights exact by clipping, disk and "
        "sphere lights by clipping and integrating arcs, their stated error in `NAME.bound`; the "
        "exact pass finds its own pixels and no sampled pass runs except on the pixels it cannot "
        "answer, too many occluders or an alpha-tested triangle in the pyramid) or `both` (V stays "
        "sampled; `NAME.V_exact` beside it and their disagreement in oracle.json); "
        "[oracle.md](oracle.md#exact-penumbrae). Part of the cache key (`compare`)"));
    t.push_back(
        nameOption("exact_pixels", "penumbra", {"penumbra", "all"}, kAll,
                   "with --penumbra both: penumbra (pixels whose samples disagree) or all "
                   "(every sampled pixel); exact finds its own pixels",
                   "with `--penumbra both`: `penumbra` (pixels whose samples disagreed) or "
                   "`all` (every sampled pixel: a small occluder no sample met is found too). "
                   "`exact` needs no choice: it computes every pixel"));
    t.push_back(
        realOption("bound_target", 1e-6, 1e-7, 0.5, kAll,
                   "disk and sphere lights with --penumbra exact, both or auto: the stated "
                   "error above which a pixel counts as missing its target",
                   "disk and sphere lights with `--penumbra exact`, `both` or `auto` (where it "
                   "chose exact): a pixel whose stated error (`NAME.bound`, about 1e-8) is above "
                   "it counts in `exact_penumbra.bound.pixels_target_missed` "
                   "([oracle.md](oracle.md#disk-and-sphere-lights))"));
    // The range is oracle/disk_bounds.h's (DiskBoundOptions::minSides, which TraceOptionTable.*
    // holds to this, and kMaxDiskSides, which is kMaxBoundSides).
    t.push_back(
        integerOption("bound_max_sides", 4096, 32, kMaxBoundSides, kAll,
                      "the most sides of the polygons bounding a disk (the independent check, "
                      "not the exact pass), a power of two in [32, " +
                          std::to_string(kMaxBoundSides) + "]",
                      "the most sides of the polygons that bound a disk "
                      "(`oracle/disk_bounds.h`: the exact pass's independent check in the "
                      "tests; the exact pass itself does not use it)"));
    t.back().powerOfTwo = true;
    return t;
}

}  // namespace

const OptionTable& traceOptions() {
    static const std::vector<OptionSpec> rows = makeTable();
    static const OptionTable table{"trace option", rows};
    return table;
}

std::span<const TraceOptionSpec> traceOptionTable() {
    return traceOptions().rows;
}

const TraceOptionSpec& traceOption(const std::string& key) {
    return traceOptions().at(key);
}

}  // namespace so
