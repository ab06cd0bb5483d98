#include "raster_compare/gl/plugin_axis.h"

#include <stdexcept>

namespace so {

namespace {

bool sameValues(const ParamSpec& a, const ParamSpec& b) {
    return a.defaultValue == b.defaultValue && a.min == b.min && a.max == b.max &&
           a.integer == b.integer && a.allowed == b.allowed && a.names == b.names &&
           a.maxExclusive == b.maxExclusive;
}

}  // namespace

ParamSpec axisParam(const PluginAxis& axis, int defaultIndex, std::string doc) {
    std::vector<std::string> names;
    for (const AxisPlugin& p : axis.plugins) names.push_back(p.name);
    ParamSpec spec = methodParam(axis.parameter, defaultIndex, std::move(names), std::move(doc));
    for (const AxisPlugin& p : axis.plugins) spec.provenances.push_back(p.provenance);
    spec.formerValues = axis.formerValues;
    return spec;
}

ParamTable axisParams(const PluginAxis& axis) {
    ParamTable merged;
    std::vector<std::vector<std::string>> declaredBy;  // per merged parameter: its plug-ins
    for (const AxisPlugin& plugin : axis.plugins)
        for (const ParamSpec& spec : plugin.params) {
            size_t i = 0;
            while (i < merged.size() && merged[i].name != spec.name) ++i;
            if (i == merged.size()) {
                merged.push_back(spec);
                declaredBy.emplace_back();
            } else if (!sameValues(merged[i], spec)) {
                throw std::invalid_argument(axis.name + " " + plugin.name + ": parameter \"" +
                                            spec.name + "\" differs from another plug-in's");
            }
            declaredBy[i].push_back(plugin.name);
        }
    for (size_t i = 0; i < merged.size(); ++i) {
        std::string names, alternatives;
        for (const std::string& n : declaredBy[i]) {
            names += (names.empty() ? "" : ", ") + n;
            alternatives += (alternatives.empty() ? "" : "|") + n;
        }
        merged[i].needs = axis.parameter + "=" + alternatives;
        merged[i].doc = names + ": " + merged[i].doc;
        merged[i].pluginParam = true;  // left out of the values unless its plug-in is chosen
    }
    return merged;
}

}  // namespace so
