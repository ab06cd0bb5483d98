// The API's comparison: raster_compare/pipeline/comparison.h's compareWithOracle, with renderers'
// images given in memory or read as `compare --image` reads them.

#include <nlohmann/json.hpp>

#include "api/api_internal.h"
#include "core/visibility_image.h"
#include "raster_compare/pipeline/compare_output.h"

namespace shadow_oracle {

namespace {

// An image given in memory, checked as readVisibilityImage checks a file: a plane per light of
// the oracle's size, every value finite and in [0, 1] up to the tolerance (then clamped).
so::ImageInput imageInput(const ExternalImage& in, const so::Scene& scene, int width, int height) {
    const std::string file =
        in.path.empty() ? "image \"" + so::printable(in.label, 60) + "\"" : in.path;
    if (in.label.empty()) so::throwInputError("image", "label", "empty");
    if (in.visibility.size() != scene.lights.size())
        so::throwInputError(file, "visibility",
                            std::to_string(in.visibility.size()) + " planes for the scene's " +
                                std::to_string(scene.lights.size()) + " lights");
    so::VisibilityImage v;
    v.path = file;
    v.width = width;
    v.height = height;
    const size_t pixels = size_t(width) * size_t(height);
    for (size_t li = 0; li < in.visibility.size(); ++li) {
        const std::string field = scene.lights[li].name + ".V";
        std::vector<float> plane = in.visibility[li];
        if (plane.size() != pixels)
            so::throwInputError(file, field,
                                std::to_string(plane.size()) + " values, the oracle's image is " +
                                    std::to_string(width) + " x " + std::to_string(height));
        so::checkVisibilityValues(file, field, plane, width);
        v.v.push_back(std::move(plane));
    }
    if (!in.renderer.empty() || in.frameMs || in.shadowMs || in.memoryBytes)
        v.cost = so::ExternalCost{in.renderer, in.frameMs, in.shadowMs, in.memoryBytes,
                                  nlohmann::json::object()};
    return {so::makeImageSpec(in.label, file), std::move(v)};
}

LightMetrics lightMetrics(const so::LightComparison& lc) {
    LightMetrics out;
    out.light = lc.light;
    for (const auto& [name, value] : so::flatMetrics(lc.toJson())) {
        std::optional<double> v;
        if (value.is_number()) v = value.get<double>();
        if (value.is_boolean()) v = value.get<bool>() ? 1.0 : 0.0;
        out.values.emplace_back(name, v);
    }
    return out;
}

}  // namespace

std::optional<double> LightMetrics::get(const std::string& name) const {
    for (const auto& [key, value] : values)
        if (key == name) return value;
    throw Error("metrics: no metric \"" + so::printable(name, 60) + "\" (docs/metrics.md)");
}

ExternalImage readImage(const Scene& scene, const std::string& label, const std::string& path,
                        int width, int height, const std::string& encoding) {
    return detail::translated([&] {
        const so::Scene& s = scene.data().scene;
        so::VisibilityImage v = so::readVisibilityImage(
            path, s.lights, width, height, so::parseImageEncoding(encoding, "options", "encoding"));
        ExternalImage out;
        out.label = label;
        out.path = path;
        out.visibility = std::move(v.v);
        if (v.cost) {
            out.renderer = v.cost->renderer;
            out.frameMs = v.cost->frameMs;
            out.shadowMs = v.cost->shadowMs;
            out.memoryBytes = v.cost->memoryBytes;
        }
        return out;
    });
}

CompareResult compare(const Scene& scene, const TraceResult& oracle,
                      const CompareOptions& options) {
    return detail::translated([&] {
        if (!oracle.data)
            so::throwInputError("compare", "oracle", "not a result of trace() on this scene");
        const so::Scene& s = scene.data().scene;
        const so::CachedOracle& o = oracle.data->oracle;
        if (o.stats.lights.size() != s.lights.size())
            so::throwInputError("compare", "oracle", "traced on another scene (other lights)");
        so::checkTechniquesAtPoints(o.atPoints, options.techniques.size(), "compare", "techniques",
                                    "techniques");
        std::vector<so::TechniqueSpec> techniques;
        for (const std::string& t : options.techniques)
            techniques.push_back(so::parseTechniqueSpec(t));
        std::vector<so::ImageInput> images;
        for (const ExternalImage& in : options.images)
            images.push_back(imageInput(in, s, o.image.width(), o.image.height()));
        so::ComparisonOptions c;
        c.raster = detail::rasterOptions(o.image.width(), o.image.height(), options.frames,
                                         options.warmup, "compare options");
        so::checkOptions(so::compareOptionTable(),
                         {{"boundary_radius", {double(options.boundaryRadius), ""}}},
                         {"compare options", false, "", false});
        c.boundaryRadius = options.boundaryRadius;
        c.contactThresholdRelative = options.contactThresholdRelative;
        c.progress = detail::toLibrary(options.progress);
        so::Comparison comparison = so::compareWithOracle(s, o, techniques, images, c);
        CompareResult out;
        out.warnings = comparison.warnings;
        out.metricsJson =
            so::metricsJson(s, s.path.string(), o, comparison, options.boundaryRadius).dump();
        for (const so::ComparedRow& row : comparison.rows) {
            ComparedRow r{row.report.row.label,
                          row.source,
                          row.technique,
                          row.report.row.family,
                          {},
                          {},
                          detail::toApi(so::errorImage(row.report))};
            for (const so::LightComparison& lc : row.report.lights)
                r.lights.push_back(lightMetrics(lc));
            so::ChannelImage image = row.report.image;
            r.image = detail::toApi(std::move(image));
            out.rows.push_back(std::move(r));
        }
        out.data = std::make_shared<const CompareResult::Data>(
            CompareResult::Data{std::move(comparison), options.boundaryRadius});
        return out;
    });
}

}  // namespace shadow_oracle
