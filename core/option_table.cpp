#include "core/option_table.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/json_reader.h"

namespace so {

namespace {

OptionSpec numberOption(OptionType type, const std::string& key, double def, double min, double max,
                        unsigned surfaces, std::string help, std::string doc) {
    OptionSpec s;
    s.cli = "--";
    for (char c : key) s.cli += c == '_' ? '-' : c;
    s.key = key;
    s.type = type;
    s.defaultValue = {def, ""};
    s.min = min;
    s.max = max;
    s.surfaces = surfaces;
    s.help = std::move(help);
    s.doc = std::move(doc);
    return s;
}

// Bounds as the errors and the docs write them: 0.0001, 1048576.
std::string numberText(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.12g", v);
    return buf;
}

// Bounds as docs/cli.md writes them: 2^20 rather than 1048576.
std::string docNumber(double v) {
    for (int k = 16; k <= 32; ++k) {
        if (v == std::ldexp(1.0, k)) return "2^" + std::to_string(k);
        if (v == std::ldexp(1.0, k) - 1) return "2^" + std::to_string(k) + " - 1";
    }
    return numberText(v);
}

std::string valueText(const OptionSpec& s, const OptionValue& v) {
    if (s.type == OptionType::Flag) return v.number != 0.0 ? "on" : "off";
    return s.type == OptionType::Name ? v.text : numberText(v.number);
}

// The surfaces by their names in optionsJson, in the docs' order.
constexpr std::pair<unsigned, const char*> kSurfaceNames[] = {{kSurfaceTrace, "trace"},
                                                              {kSurfaceRaster, "raster"},
                                                              {kSurfaceCompare, "compare"},
                                                              {kSurfaceSweep, "sweep"},
                                                              {kSurfaceApi, "api"}};

std::string rangeText(const OptionSpec& s) {
    std::string range;
    if (s.type == OptionType::Name) {
        for (const std::string& n : s.names) range += (range.empty() ? "" : ", ") + n;
        return range;
    }
    if (s.type == OptionType::Flag) return "on (given) or off";
    range = docNumber(s.min) + " .. " + docNumber(s.max);
    return s.powerOfTwo ? "a power of two, " + range : range;
}

}  // namespace

const char* optionTypeName(OptionType t) {
    switch (t) {
        case OptionType::Integer:
            return "integer";
        case OptionType::Real:
            return "real";
        case OptionType::Name:
            return "name";
        case OptionType::Flag:
            return "flag";
    }
    return "?";
}

const OptionSpec& OptionTable::at(const std::string& key) const {
    for (const OptionSpec& s : rows)
        if (s.key == key) return s;
    throw std::invalid_argument(std::string("no ") + kind + " " + key);
}

OptionSpec integerOption(const std::string& key, double def, double min, double max,
                         unsigned surfaces, std::string help, std::string doc) {
    return numberOption(OptionType::Integer, key, def, min, max, surfaces, std::move(help),
                        std::move(doc));
}

OptionSpec realOption(const std::string& key, double def, double min, double max, unsigned surfaces,
                      std::string help, std::string doc) {
    return numberOption(OptionType::Real, key, def, min, max, surfaces, std::move(help),
                        std::move(doc));
}

OptionSpec flagOption(const std::string& key, unsigned surfaces, std::string help,
                      std::string doc) {
    return numberOption(OptionType::Flag, key, 0, 0, 1, surfaces, std::move(help), std::move(doc));
}

OptionSpec nameOption(const std::string& key, const std::string& def,
                      std::vector<std::string> names, unsigned surfaces, std::string help,
                      std::string doc) {
    OptionSpec s =
        numberOption(OptionType::Name, key, 0, 0, 0, surfaces, std::move(help), std::move(doc));
    s.defaultValue = {0.0, def};
    s.names = std::move(names);
    return s;
}

OptionSpec zeroMeans(OptionSpec s, std::string text) {
    s.unsetZero = true;
    s.defaultText = std::move(text);
    return s;
}

OptionSpec sameResult(OptionSpec s) {
    s.changesResult = false;
    return s;
}

void checkOption(const OptionSpec& spec, const OptionValue& v, const std::string& file,
                 const std::string& field, bool allowUnsetZero) {
    if (spec.type == OptionType::Name) {
        for (const std::string& n : spec.names)
            if (v.text == n) return;
        // The JSON reader's wording for a name not in a list (docs/scene-format.md, "One wording").
        throwInputError(file, field,
                        "unknown value \"" + printable(v.text, 40) +
                            "\" (valid: " + JsonReader::list(spec.names) + ")");
    }
    const double x = v.number;
    if (allowUnsetZero && spec.unsetZero && x == 0.0) return;
    const bool integer = spec.type == OptionType::Integer || spec.type == OptionType::Flag;
    const std::string range = "[" + numberText(spec.min) + ", " + numberText(spec.max) + "]";
    if (spec.powerOfTwo) {
        const bool ok = x >= spec.min && x <= spec.max && x == std::floor(x) &&
                        (uint64_t(x) & (uint64_t(x) - 1)) == 0;
        if (!ok) throwInputError(file, field, numberText(x) + " is not a power of two in " + range);
        return;
    }
    if (!(x >= spec.min && x <= spec.max) || (integer && x != std::floor(x)))
        throwInputError(
            file, field,
            std::string("must be ") + (integer ? "an integer in " : "in ") + range +
                (allowUnsetZero && spec.unsetZero ? " or 0 (" + spec.defaultText + ")" : "") +
                ", got " + numberText(x));
}

void checkOptions(const OptionTable& table, const OptionValues& values,
                  const OptionNaming& naming) {
    for (const auto& [key, value] : values) {
        const OptionSpec& spec = table.at(key);
        checkOption(spec, value, naming.file, naming.field(spec), naming.allowUnsetZero);
    }
}

std::string optionDefaultText(const OptionSpec& s) {
    return s.defaultText.empty() ? valueText(s, s.defaultValue) : s.defaultText;
}

std::string optionHelp(const OptionSpec& s) {
    return s.help + " (default: " + optionDefaultText(s) + ")";
}

std::string optionsMarkdown(const OptionTable& table) {
    std::ostringstream out;
    out << "| option | API, Python, sweep key | default | range | meaning | offered by |\n"
        << "|---|---|---|---|---|---|\n";
    for (const OptionSpec& s : table.rows) {
        std::string doc = s.doc;
        if (!s.excludes.empty()) {
            doc += "; not with";
            for (size_t i = 0; i < s.excludes.size(); ++i)
                doc += std::string(i == 0                       ? " "
                                   : i + 1 == s.excludes.size() ? " or "
                                                                : ", ") +
                       "`" + table.at(s.excludes[i]).cli + "`";
        }
        out << "| `" << s.cli << "` | `" << s.key << "` | " << optionDefaultText(s) << " | "
            << rangeText(s) << " | " << doc << " |";
        const char* separator = " ";
        for (const auto& [bit, n] : kSurfaceNames)
            if (s.surfaces & bit) {
                out << separator << (bit == kSurfaceApi ? "API, Python" : n);
                separator = ", ";
            }
        out << " |\n";
    }
    return out.str();
}

std::string optionsJson(const OptionTable& table) {
    nlohmann::ordered_json options = nlohmann::ordered_json::array();
    for (const OptionSpec& s : table.rows) {
        nlohmann::ordered_json j;
        j["cli"] = s.cli;
        j["key"] = s.key;
        j["type"] = optionTypeName(s.type);
        if (s.type == OptionType::Integer)
            j["default"] = int64_t(s.defaultValue.number);
        else if (s.type == OptionType::Real)
            j["default"] = s.defaultValue.number;
        else if (s.type == OptionType::Flag)
            j["default"] = s.defaultValue.number != 0.0;
        else
            j["default"] = s.defaultValue.text;
        if (s.type == OptionType::Name) {
            j["names"] = s.names;
        } else {
            j["min"] = s.min;
            j["max"] = s.max;
            j["power_of_two"] = s.powerOfTwo;
            j["zero_means_default"] = s.unsetZero;
        }
        j["default_text"] = s.defaultText;
        j["help"] = s.help;
        j["excludes"] = s.excludes;
        j["surfaces"] = nlohmann::ordered_json::array();
        for (const auto& [bit, n] : kSurfaceNames)
            if (s.surfaces & bit) j["surfaces"].push_back(n);
        options.push_back(std::move(j));
    }
    return nlohmann::ordered_json{{"format_version", 1}, {"options", options}}.dump(2) + "\n";
}

}  // namespace so
