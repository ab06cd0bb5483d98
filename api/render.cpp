// The API's GL path: one technique rendered, as `shadow-oracle raster` does.
#include <nlohmann/json.hpp>

#include "api/api_internal.h"
#include "core/compare_option_table.h"
#include "core/trace_option_table.h"
#include "raster_compare/gl/context/gl_context.h"
#include "raster_compare/gl/render/raster_options.h"
#include "raster_compare/gl/render/renderer.h"
#include "raster_compare/gl/technique_listing.h"

namespace shadow_oracle {

std::string techniquesJson() {
    return detail::translated([] { return so::techniquesListing(so::ListingFormat::Json); });
}

so::RasterOptions detail::rasterOptions(int width, int height, int frames, int warmup,
                                        const std::string& file) {
    // The image size by the trace options' rows (0: the scene camera's), the rest by the raster's.
    so::checkTraceOptions({{"width", {double(width), ""}}, {"height", {double(height), ""}}},
                          {file, false, "", /*allowUnsetZero=*/true});
    so::RasterOptions o;
    o.width = width;
    o.height = height;
    so::applyRasterOptions({{"frames", {double(frames), ""}}, {"warmup", {double(warmup), ""}}},
                           {file, false, "", false}, o);
    return o;
}

RenderResult render(const Scene& scene, const std::string& technique, const Parameters& parameters,
                    const RenderOptions& options) {
    return detail::translated([&] {
        std::vector<std::string> settings;
        for (const auto& [key, value] : parameters) settings.push_back(key + "=" + value);
        const std::unique_ptr<so::Technique> t = so::createTechnique(technique, settings);
        so::RasterOptions o = detail::rasterOptions(options.width, options.height, options.frames,
                                                    options.warmup, "render options");
        if (options.converge != 0)  // 0: not given, one frame (the row's default)
            so::checkOptions(so::compareOptionTable(),
                             {{"converge", {double(options.converge), ""}}},
                             {"render options", false, "", false});
        o.converge = options.converge;
        so::GlContext gl;
        so::RasterResult r = so::renderConverged(scene.data().scene, *t, o, gl);
        RenderResult out;
        out.frameMs = r.stats.timings.wallMs.median;
        out.statsJson = so::toJson(r.stats).dump();
        out.warnings = t->values().deprecations();  // a former parameter name
        for (std::string& w : gl.takeWarnings()) out.warnings.push_back(std::move(w));
        out.data = std::make_shared<const RenderResult::Data>(
            RenderResult::Data{t->name(), r.image, r.stats});  // writeRenderOutput's copy
        out.image = detail::toApi(std::move(r.image));
        return out;
    });
}

}  // namespace shadow_oracle
