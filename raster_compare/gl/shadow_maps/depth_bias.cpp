#include "raster_compare/gl/shadow_maps/depth_bias.h"

#include <algorithm>
#include <stdexcept>
#include <string>

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
        std::vector<BiasInfo> byNumber = r.all();
        std::sort(byNumber.begin(), byNumber.end(),
                  [](const BiasInfo& a, const BiasInfo& b) { return a.number < b.number; });
        for (size_t i = 0; i < byNumber.size(); ++i)
            if (byNumber[i].number != int(i))
                throw std::invalid_argument("bias \"" + byNumber[i].name + "\": number " +
                                            std::to_string(byNumber[i].number) + ", expected " +
                                            std::to_string(i) + " (no gaps, none twice)");
        return byNumber;
    }();
    return all;
}

PluginAxis biasAxis() {
    PluginAxis axis{"bias", "shadow map", "bias", {}};
    for (const BiasInfo& b : allBiases())
        axis.plugins.push_back({b.name, b.summary, b.params, b.provenance});
    // Issue 63: `oriented` claimed FFXVI's talk, which was not read; the same bias, our own.
    axis.formerValues = {{"oriented", "half-texel", 8}};
    return axis;
}

ParamTable biasAxisParams(const std::string& defaultBias) {
    const PluginAxis axis = biasAxis();
    int defaultIndex = -1;
    for (size_t i = 0; i < axis.plugins.size(); ++i)
        if (axis.plugins[i].name == defaultBias) defaultIndex = int(i);
    if (defaultIndex < 0)
        throw std::invalid_argument("biasAxisParams: no bias \"" + defaultBias + "\"");
    ParamTable table = {axisParam(axis, defaultIndex,
                                  "the depth bias (biases/; `shadow-oracle techniques` lists each "
                                  "with its parameters)")};
    for (ParamSpec& s : axisParams(axis)) table.push_back(std::move(s));
    return table;
}

std::string biasName(const ParamValues& values) {
    return allBiases().at(size_t(values.integer("bias"))).name;
}

std::unique_ptr<DepthBias> createDepthBias(const ParamValues& values) {
    return allBiases().at(size_t(values.integer("bias"))).create(values);
}

}  // namespace so
