#include "raster_compare/technique.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/error.h"

namespace so {

std::vector<ParamSpec> ShadowTechnique::params() const {
    std::vector<ParamSpec> p = {
        {"resolution", 2048, 16, 16384, true, "shadow map side in texels (cube maps: per face)"},
        {"depth_format", 24, 16, 32, true, "depth buffer bits: 16, 24 (fixed point) or 32 (float)"},
        {"fit", 0, 0, 1, true,
         "directional maps: 0 fit the scene's bounds, 1 only the receivers in view"},
    };
    for (const ParamSpec& s : ownParams()) p.push_back(s);
    return p;
}

ParamValues ShadowTechnique::parse(const std::vector<std::string>& settings) const {
    const std::vector<ParamSpec> specs = params();
    ParamValues values;
    for (const ParamSpec& s : specs) values[s.name] = s.defaultValue;
    std::string valid;
    for (const ParamSpec& s : specs) valid += (valid.empty() ? "" : ", ") + s.name;
    const std::string file = "technique " + name();
    for (const std::string& setting : settings) {
        const auto eq = setting.find('=');
        if (eq == std::string::npos || eq == 0)
            throwInputError(file, printable(setting, 40),
                            "expected key=value (valid keys: " + valid + ")");
        const std::string key = setting.substr(0, eq), text = setting.substr(eq + 1);
        const ParamSpec* spec = nullptr;
        for (const ParamSpec& s : specs)
            if (s.name == key) spec = &s;
        if (!spec)
            throwInputError(file, printable(key, 40), "unknown parameter (valid: " + valid + ")");
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0' || !std::isfinite(v))
            throwInputError(file, key, "\"" + printable(text, 40) + "\" is not a number");
        if (spec->integer && v != std::floor(v)) throwInputError(file, key, "must be an integer");
        if (v < spec->min || v > spec->max) {
            std::ostringstream os;
            os << v << " is out of range [" << spec->min << ", " << spec->max << "]";
            throwInputError(file, key, os.str());
        }
        if (key == "depth_format" && v != 16 && v != 24 && v != 32)
            throwInputError(file, key, "must be 16, 24 or 32");
        values[key] = v;
    }
    return values;
}

std::vector<ParamSpec> slopeBiasParams() {
    return {{"alpha", 1.0, 0.0, 100.0, false, "slope factor"},
            {"min", 0.1, 0.0, 1000.0, false, "smallest bias in texels"},
            {"max", 10.0, 0.0, 1000.0, false, "largest bias in texels"}};
}

std::string slopeBiasDefines(const ParamValues& p) {
    return "#define BIAS_SLOPE_ALPHA " + std::to_string(p.at("alpha")) +
           "\n#define BIAS_SLOPE_MIN " + std::to_string(p.at("min")) + "\n#define BIAS_SLOPE_MAX " +
           std::to_string(p.at("max")) + "\n";
}

const std::vector<const ShadowTechnique*>& allTechniques() {
    static const std::vector<const ShadowTechnique*> all = {
        &basicTechnique(),         &biasTechnique(),         &slopeBiasTechnique(),
        &polygonOffsetTechnique(), &normalOffsetTechnique(), &pcfTechnique(),
        &backFacesTechnique(),     &hwPcfTechnique(),        &vsmTechnique(),
        &esmTechnique(),           &evsmTechnique()};
    return all;
}

const ShadowTechnique& findTechnique(const std::string& name) {
    std::string valid;
    for (const ShadowTechnique* t : allTechniques()) {
        if (t->name() == name) return *t;
        valid += (valid.empty() ? "" : ", ") + t->name();
    }
    throwInputError("command line", "--technique",
                    "unknown technique \"" + printable(name, 40) + "\" (valid: " + valid + ")");
}

}  // namespace so
