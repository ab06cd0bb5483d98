#include "raster_compare/gl/params.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "core/error.h"

namespace so {

double ParamValues::real(const std::string& name) const {
    const auto it = values_.find(name);
    SO_CHECK(it != values_.end());
    return it->second;
}

int ParamValues::integer(const std::string& name) const {
    return int(real(name));
}

std::map<std::string, ParamSetting> ParamValues::settings() const {
    std::map<std::string, ParamSetting> out;
    for (const auto& [name, v] : values_) out[name] = {v, integer_.at(name)};
    return out;
}

namespace {

std::string listOf(const std::vector<double>& values) {
    std::ostringstream os;
    for (size_t i = 0; i < values.size(); ++i) os << (i ? ", " : "") << values[i];
    return os.str();
}

void validate(const std::string& file, const ParamSpec& spec, double v) {
    if (spec.integer && v != std::floor(v)) throwInputError(file, spec.name, "must be an integer");
    if (v < spec.min || v > spec.max) {
        std::ostringstream os;
        os << v << " is out of range [" << spec.min << ", " << spec.max << "]";
        throwInputError(file, spec.name, os.str());
    }
    if (!spec.allowed.empty()) {
        for (double a : spec.allowed)
            if (a == v) return;
        throwInputError(file, spec.name, "must be one of " + listOf(spec.allowed));
    }
}

}  // namespace

ParamValues parseParams(const std::string& technique, const ParamTable& table,
                        const std::vector<std::string>& settings) {
    ParamValues values;
    std::string valid;
    for (const ParamSpec& s : table) {
        values.values_[s.name] = s.defaultValue;
        values.integer_[s.name] = s.integer;
        valid += (valid.empty() ? "" : ", ") + s.name;
    }
    if (valid.empty()) valid = "none, the technique has no parameters";
    const std::string file = "technique " + technique;
    for (const std::string& setting : settings) {
        const auto eq = setting.find('=');
        if (eq == std::string::npos || eq == 0)
            throwInputError(file, printable(setting, 40),
                            "expected key=value (valid keys: " + valid + ")");
        const std::string key = setting.substr(0, eq), text = setting.substr(eq + 1);
        const ParamSpec* spec = nullptr;
        for (const ParamSpec& s : table)
            if (s.name == key) spec = &s;
        if (!spec)
            throwInputError(file, printable(key, 40), "unknown parameter (valid: " + valid + ")");
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0' || !std::isfinite(v))
            throwInputError(file, key, "\"" + printable(text, 40) + "\" is not a number");
        validate(file, *spec, v);
        values.values_[key] = v;
    }
    return values;
}

std::string glslFloat(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    std::string s = buf;
    // Without a '.' or an exponent GLSL reads an int.
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return s;
}

std::string glslDefine(const std::string& name, double v) {
    return "#define " + name + " " + glslFloat(v) + "\n";
}

const ParamSpec* qualityParam(const ParamTable& table) {
    for (const ParamSpec& p : table)
        if (p.quality) return &p;
    return nullptr;
}

}  // namespace so
