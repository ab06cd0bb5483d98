#include "raster_compare/gl/params.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "core/error.h"

namespace so {

double ParamValues::real(const std::string& name) const {
    const auto it = values_.find(name);
    // A technique asking for a name its own table lacks: a slip in its code, not the user's.
    if (it == values_.end())
        throw std::invalid_argument("technique parameter \"" + printable(name) +
                                    "\" is not in the technique's table");
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

// "grid, poisson" (or their numbers, 0..1).
std::string namesOf(const ParamSpec& spec) {
    std::string s;
    for (const std::string& n : spec.names) s += (s.empty() ? "" : ", ") + n;
    return s + ", or their numbers 0.." + std::to_string(spec.names.size() - 1);
}

// v, converted to the parameter's current meaning where it was given under `formerKey`.
void validate(const std::string& file, const ParamSpec& spec, double v,
              const std::string& formerKey) {
    const std::string field = formerKey.empty() ? spec.name : formerKey;
    if (spec.integer && v != std::floor(v)) throwInputError(file, field, "must be an integer");
    std::ostringstream os;
    if (!formerKey.empty()) os << "gives " << spec.name << " = ";
    if (v < spec.min || v > spec.max || (spec.maxExclusive && v == spec.max)) {
        os << v << (formerKey.empty() ? " is" : ",") << " out of range [" << spec.min << ", "
           << spec.max << (spec.maxExclusive ? ")" : "]");
        throwInputError(file, field, os.str());
    }
    if (!spec.allowed.empty()) {
        for (double a : spec.allowed)
            if (a == v) return;
        throwInputError(file, field, "must be one of " + listOf(spec.allowed));
    }
}

}  // namespace

namespace {

// The first need along spec's chain that the values do not meet ("contact=on" for a parameter that
// needs contact_method=bevy, whose contact_method needs contact=on); empty when all are met. A
// parameter needs what the setting it needs needs: a method's own parameter means nothing while
// the method parameter itself means nothing.
std::string unmetNeed(const ParamSpec& spec, const ParamTable& table, const ParamValues& values) {
    if (spec.needs.empty()) return "";
    const size_t eq = spec.needs.find('=');
    const std::string key = spec.needs.substr(0, eq);
    std::vector<std::string> texts;
    for (size_t from = eq + 1;;) {
        const size_t bar = spec.needs.find('|', from);
        texts.push_back(spec.needs.substr(from, bar == std::string::npos ? bar : bar - from));
        if (bar == std::string::npos) break;
        from = bar + 1;
    }
    for (const ParamSpec& other : table) {
        if (other.name != key) continue;
        bool met = false;
        for (const std::string& text : texts) {
            const auto named = std::find(other.names.begin(), other.names.end(), text);
            const double wanted = named != other.names.end() ? double(named - other.names.begin())
                                                             : std::strtod(text.c_str(), nullptr);
            met = met || values.real(key) == wanted;
        }
        return met ? unmetNeed(other, table, values) : spec.needs;
    }
    return "";
}

}  // namespace

bool needsMet(const ParamSpec& spec, const ParamTable& table, const ParamValues& values) {
    return unmetNeed(spec, table, values).empty();
}

namespace {

// Every given parameter whose table entry needs another setting has it (ParamSpec::needs).
void checkNeeds(const std::string& file, const ParamTable& table, const ParamValues& values) {
    for (const ParamSpec& s : table)
        if (const std::string unmet = values.given(s.name) ? unmetNeed(s, table, values) : "";
            !unmet.empty())
            throwInputError(file, s.name, "has no effect without " + unmet);
}

// The spec a key names: its own name, else a former name (`former` set then); null: none.
const ParamSpec* specOfKey(const ParamTable& table, const std::string& key, bool& former) {
    former = false;
    for (const ParamSpec& s : table)
        if (s.name == key) return &s;
    for (const ParamSpec& s : table)
        if (s.former && s.former->name == key) {
            former = true;
            return &s;
        }
    return nullptr;
}

// "technique raytraced: `alpha` is deprecated, use `history` (history = 1 - alpha); accepted
// until format 8".
std::string deprecationNotice(const std::string& file, const ParamSpec& spec) {
    const FormerName& f = *spec.former;
    return file + ": `" + f.name + "` is deprecated, use `" + spec.name + "`" +
           (f.relation.empty() ? "" : " (" + f.relation + ")") + "; accepted until format " +
           std::to_string(f.untilFormat);
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
    std::map<std::string, std::string> spelledAs;  // parameter -> the key that set it
    for (const std::string& setting : settings) {
        const auto eq = setting.find('=');
        if (eq == std::string::npos || eq == 0)
            throwInputError(file, printable(setting, 40),
                            "expected key=value (valid keys: " + valid + ")");
        const std::string key = setting.substr(0, eq), text = setting.substr(eq + 1);
        bool former = false;
        const ParamSpec* spec = specOfKey(table, key, former);
        if (!spec)
            throwInputError(file, printable(key, 40), "unknown parameter (valid: " + valid + ")");
        auto named = std::find(spec->names.begin(), spec->names.end(), text);
        for (const FormerValue& f : spec->formerValues)
            if (named == spec->names.end() && f.name == text) {
                named = std::find(spec->names.begin(), spec->names.end(), f.current);
                const std::string notice =
                    file + ": `" + key + "=" + f.name + "` is deprecated, use `" + key + "=" +
                    f.current + "`; accepted until format " + std::to_string(f.untilFormat);
                std::vector<std::string>& notices = values.deprecations_;
                if (std::find(notices.begin(), notices.end(), notice) == notices.end())
                    notices.push_back(notice);
            }
        char* end = nullptr;
        double v = named != spec->names.end() ? double(named - spec->names.begin())
                                              : std::strtod(text.c_str(), &end);
        if (named == spec->names.end() && (text.empty() || *end != '\0' || !std::isfinite(v)))
            // A name not in the list in the JSON reader's words (docs/scene-format.md).
            throwInputError(file, key,
                            spec->names.empty() ? "\"" + printable(text, 40) + "\" is not a number"
                                                : "unknown value \"" + printable(text, 40) +
                                                      "\" (valid: " + namesOf(*spec) + ")");
        // The same key twice: the last one holds, as ever; a name and its former name: an error.
        const auto spelled = spelledAs.emplace(spec->name, key).first;
        if (spelled->second != key)
            throwInputError(file, key,
                            "given twice (`" + spec->former->name + "` is the former name of `" +
                                spec->name + "`)");
        if (former && spec->former->toCurrent) v = spec->former->toCurrent(v);
        validate(file, *spec, v, former ? key : "");
        std::vector<std::string>& notices = values.deprecations_;
        if (former && std::find(notices.begin(), notices.end(), deprecationNotice(file, *spec)) ==
                          notices.end())
            notices.push_back(deprecationNotice(file, *spec));  // once per former name
        values.values_[spec->name] = v;
        values.given_.insert(spec->name);
    }
    checkNeeds(file, table, values);
    // The parameters of the axes' plug-ins that were not chosen.
    for (const ParamSpec& s : table)
        if (s.pluginParam && !needsMet(s, table, values)) {
            values.values_.erase(s.name);
            values.integer_.erase(s.name);
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

ParamSpec methodParam(std::string name, int defaultIndex, std::vector<std::string> names,
                      std::string doc) {
    if (names.size() < 2 || defaultIndex < 0 || size_t(defaultIndex) >= names.size())
        throw std::invalid_argument("methodParam \"" + name + "\": needs two names or more and a " +
                                    "default among them");
    ParamSpec p{std::move(name), double(defaultIndex), 0.0, double(names.size() - 1), true,
                std::move(doc)};
    p.names = std::move(names);
    return p;
}

ParamSpec renamedFrom(ParamSpec spec, FormerName former) {
    spec.former = std::move(former);
    return spec;
}

std::string paramValueText(const ParamSpec& spec, double v) {
    if (!spec.names.empty() && v >= 0 && v < double(spec.names.size()) && v == std::floor(v))
        return spec.names[size_t(v)];
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

std::string neededSetting(const ParamSpec& spec) {
    return spec.needs.substr(0, spec.needs.find('|'));
}

std::vector<std::string> neededSettings(const ParamSpec& spec, const ParamTable& table) {
    std::vector<std::string> settings;
    for (const ParamSpec* s = &spec; s && !s->needs.empty();) {
        settings.insert(settings.begin(), neededSetting(*s));
        const std::string key = s->needs.substr(0, s->needs.find('='));
        const ParamSpec* next = nullptr;
        for (const ParamSpec& other : table)
            if (other.name == key) next = &other;
        s = next;
    }
    return settings;
}

const ParamSpec* qualityParam(const ParamTable& table) {
    for (const ParamSpec& p : table)
        if (p.quality) return &p;
    return nullptr;
}

}  // namespace so
