#include "raster_compare/gl/denoisers/denoiser.h"

#include <stdexcept>

#include "core/error.h"

namespace so {

namespace {

// Built on first use from the generated list (a function-local static), never modified after.
const std::vector<const DenoiserInfo*>& registry() {
    static const DenoiserRegistry r = [] {
        DenoiserRegistry built;
        registerBuiltInDenoisers(built);
        return built;
    }();
    static const std::vector<const DenoiserInfo*> byNumber = r.inOrder();
    return byNumber;
}

}  // namespace

const std::vector<const DenoiserInfo*>& allDenoisers() {
    return registry();
}

PluginAxis denoiserAxis() {
    PluginAxis axis{"denoiser", kRayTracingFamily, "denoiser", {}};
    // The blocker-distance blur was `penumbra` until format 8 (issue 63: it is not the Ray Tracing
    // Gems chapter 13 design it was credited to, which is `rtg`).
    axis.formerValues = {{"penumbra", "hitdist", 8}};
    for (const DenoiserInfo* d : allDenoisers())
        axis.plugins.push_back({d->name, d->summary, d->params, d->provenance});
    return axis;
}

std::unique_ptr<Denoiser> createDenoiser(const ParamValues& values) {
    // parseParams held the number to the method parameter's range: one per denoiser.
    return allDenoisers().at(size_t(values.integer("denoiser")))->create(values);
}

ParamSpec historyParam() {
    return renamedFrom(
        {"history", 0.8, 0.0, 0.99, false,
         "the history's weight in each frame's exponential blend (SVGF section "
         "4.1: 0.8, its alpha 0.2 being the new frame's weight; pcf's and pcss's "
         "`history` means the same); a history younger than 1 / (1 - history) "
         "frames averages them equally"},
        {"alpha", [](double alpha) { return 1.0 - alpha; }, "history = 1 - alpha", 8});
}

ParamSpec sigmaLuminanceParam() {
    return {"sigma_luminance",
            4,
            0.01,
            1000,
            false,
            "V stop, in standard deviations of the 3 x 3-blurred variance (SVGF 4.2: 4)"};
}

ParamSpec sigmaNormalParam() {
    return {"sigma_normal", 128,   1,
            1024,           false, "normal stop, the power of the normals' cosine (SVGF 4.2: 128)"};
}

ParamSpec sigmaDepthParam() {
    return {"sigma_depth",
            1,
            0.01,
            1000,
            false,
            "depth stop, the distance from the pixel's tangent plane in pixel footprints per "
            "pixel of distance (SVGF 4.2: 1, on its depth gradient)"};
}

}  // namespace so
