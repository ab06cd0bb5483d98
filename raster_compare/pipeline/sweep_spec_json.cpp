#include "raster_compare/pipeline/sweep_spec_json.h"

#include <vector>

#include "core/json_reader.h"

namespace so::sweep_detail {

nlohmann::json plain(const Json& v) {
    return nlohmann::json(v);
}

void checkKeys(const Json& obj, const std::set<std::string>& allowed, const std::string& file,
               const std::string& field) {
    const JsonReader r(file);
    if (!obj.is_object()) r.requireObject(plain(obj), field);
    const std::vector<std::string> valid(allowed.begin(), allowed.end());
    for (const auto& [key, value] : obj.items()) r.checkKey(key, field, valid);
}

double number(const Json& v, const std::string& file, const std::string& field) {
    return JsonReader(file).number(plain(v), field);
}

int integer(const Json& v, const std::string& file, const std::string& field, int lo, int hi) {
    return JsonReader(file).integer(plain(v), field, lo, hi);
}

bool boolean(const Json& v, const std::string& file, const std::string& field) {
    return JsonReader(file).boolean(plain(v), field);
}

std::string string(const Json& v, const std::string& file, const std::string& field) {
    return JsonReader(file).string(plain(v), field);
}

OptionValue optionValue(const OptionSpec& spec, const Json& v, const std::string& file,
                        const std::string& field) {
    OptionValue out;
    if (spec.type == OptionType::Name) {
        out.text = string(v, file, field);
    } else if (spec.type == OptionType::Flag) {
        out.number = boolean(v, file, field) ? 1.0 : 0.0;
    } else {
        out.number = number(v, file, field);
    }
    checkOption(spec, out, file, field, /*allowUnsetZero=*/false);
    return out;
}

}  // namespace so::sweep_detail
