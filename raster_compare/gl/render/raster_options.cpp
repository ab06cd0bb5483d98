#include "raster_compare/gl/render/raster_options.h"

#include <map>

namespace so {

namespace {

using Setter = void (*)(RasterOptions& o, const OptionValue& v);

// Where each key goes.
const std::map<std::string, Setter>& setters() {
    static const std::map<std::string, Setter> kSetters = {
        {"frames", [](RasterOptions& o, const OptionValue& v) { o.frames = int(v.number); }},
        {"warmup", [](RasterOptions& o, const OptionValue& v) { o.warmup = int(v.number); }},
    };
    return kSetters;
}

}  // namespace

void applyRasterOptions(const OptionValues& values, const OptionNaming& naming, RasterOptions& o) {
    checkOptions(rasterOptionTable(), values, naming);
    for (const auto& [key, value] : values) setters().at(key)(o, value);
}

std::vector<std::string> appliedRasterOptionKeys() {
    std::vector<std::string> keys;
    for (const auto& [key, setter] : setters()) keys.push_back(key);
    return keys;
}

}  // namespace so
