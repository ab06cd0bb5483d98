#include "raster_compare/gl/shadow_maps/depth_bias.h"

#include <algorithm>
#include <stdexcept>

#include "core/error.h"

namespace so {

void BiasRegistry::add(BiasInfo info) {
    for (const BiasInfo& b : all_)
        if (b.name == info.name)
            throw std::invalid_argument("bias \"" + printable(info.name) + "\" registered twice");
    all_.push_back(std::move(info));
}

const std::vector<BiasInfo>& allBiases() {
    // Built on first use (thread-safe: a function-local static), never modified afterwards.
    static const std::vector<BiasInfo> all = [] {
        BiasRegistry r;
        registerBuiltInBiases(r);
        std::vector<BiasInfo> sorted = r.all();
        std::sort(sorted.begin(), sorted.end(), [](const BiasInfo& a, const BiasInfo& b) {
            return (a.name != "none") != (b.name != "none") ? a.name == "none" : a.name < b.name;
        });
        return sorted;
    }();
    return all;
}

ParamTable biasAxisParams(const std::string& defaultBias) {
    const std::vector<BiasInfo>& biases = allBiases();
    std::vector<std::string> names;
    int defaultIndex = -1;
    for (const BiasInfo& b : biases) {
        if (b.name == defaultBias) defaultIndex = int(names.size());
        names.push_back(b.name);
    }
    if (defaultIndex < 0)
        throw std::invalid_argument("biasAxisParams: no bias \"" + defaultBias + "\"");
    ParamTable table = {methodParam("bias", defaultIndex, names,
                                    "the depth bias (biases/, `shadow-oracle techniques` lists "
                                    "each with its parameters)")};
    for (const BiasInfo& b : biases)
        for (ParamSpec s : b.params) {
            const auto same = std::find_if(table.begin(), table.end(),
                                           [&](const ParamSpec& t) { return t.name == s.name; });
            if (same != table.end()) {
                // Shared with an earlier bias (epsilon): one parameter, needing either.
                if (same->defaultValue != s.defaultValue || same->doc != s.doc)
                    throw std::invalid_argument("bias parameter \"" + s.name +
                                                "\" has two meanings");
                same->needs += "|" + b.name;
                continue;
            }
            s.needs = "bias=" + b.name;
            s.axisParam = true;
            table.push_back(std::move(s));
        }
    return table;
}

std::string biasName(const ParamValues& values) {
    return allBiases().at(size_t(values.integer("bias"))).name;
}

std::unique_ptr<DepthBias> createDepthBias(const ParamValues& values) {
    return allBiases().at(size_t(values.integer("bias"))).create(values);
}

}  // namespace so
