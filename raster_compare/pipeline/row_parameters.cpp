#include "raster_compare/pipeline/row_parameters.h"

#include <algorithm>
#include <cmath>

#include "raster_compare/gl/technique.h"

namespace so {

namespace {

const ParamSpec* findSpec(const std::string& technique, const std::string& name) {
    const std::vector<const TechniqueInfo*> all = allTechniques();
    const auto t = std::find_if(all.begin(), all.end(),
                                [&](const TechniqueInfo* i) { return i->name == technique; });
    if (t == all.end()) return nullptr;
    const ParamTable& table = (*t)->params;
    const auto p = std::find_if(table.begin(), table.end(),
                                [&](const ParamSpec& s) { return s.name == name; });
    return p == table.end() ? nullptr : &*p;
}

}  // namespace

ParamValue typedParamValue(const std::string& technique, const std::string& name,
                           const nlohmann::json& value) {
    ParamValue v = paramValueOfJson(value);
    const ParamSpec* spec = findSpec(technique, name);
    if (!spec || spec->names.empty() || v.kind == ParamValue::Kind::Name) return v;
    const double k = v.number;
    if (k >= 0.0 && k < double(spec->names.size()) && k == std::floor(k)) {
        v.kind = ParamValue::Kind::Name;
        v.name = spec->names[size_t(k)];
    }
    return v;
}

RowParameters typedParameters(const std::string& technique, const nlohmann::json& parameters) {
    RowParameters out;
    if (!parameters.is_object()) return out;
    for (auto it = parameters.begin(); it != parameters.end(); ++it)
        out[it.key()] = typedParamValue(technique, it.key(), *it);
    return out;
}

}  // namespace so
