#include "raster_compare/gl/technique_listing.h"

#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

#include "raster_compare/gl/technique.h"

namespace so {

namespace {

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

std::string range(const ParamSpec& p) {
    if (!p.names.empty()) {
        std::string s;
        for (const std::string& n : p.names) s += (s.empty() ? "" : ", ") + n;
        return s;
    }
    if (!p.allowed.empty()) {
        std::string s;
        for (double a : p.allowed) s += (s.empty() ? "" : ", ") + number(a);
        return s;
    }
    return number(p.min) + ".." + number(p.max) +
           (p.maxExclusive ? " (below " + number(p.max) + ")" : "") +
           (p.integer ? " (integer)" : "");
}

std::string markdown() {
    std::ostringstream o;
    o << "| technique | family | what it does |\n|---|---|---|\n";
    for (const TechniqueInfo* t : allTechniques())
        o << "| [`" << t->name << "`](#" << t->name << ") | " << t->family << " | " << t->summary
          << " |\n";
    for (const TechniqueInfo* t : allTechniques()) {
        o << "\n### " << t->name << "\n\n" << t->summary << " (" << t->family << ").\n\n";
        if (t->params.empty()) {
            o << "No parameters.\n";
            continue;
        }
        o << "| parameter | default | range | meaning |\n|---|---|---|---|\n";
        for (const ParamSpec& p : t->params)
            o << "| `" << p.name << "`" << (p.quality ? " (quality)" : "") << " | "
              << paramValueText(p, p.defaultValue) << " | " << range(p) << " | " << p.doc << " |\n";
    }
    return o.str();
}

std::string text() {
    std::ostringstream o;
    for (const TechniqueInfo* t : allTechniques()) {
        o << t->name << " (" << t->family << "): " << t->summary << "\n";
        for (const ParamSpec& p : t->params)
            o << "    " << p.name << " = " << paramValueText(p, p.defaultValue) << "  [" << range(p)
              << "]  " << p.doc << "\n";
    }
    return o.str();
}

std::string json() {
    nlohmann::json all = nlohmann::json::array();
    for (const TechniqueInfo* t : allTechniques()) {
        nlohmann::json params = nlohmann::json::array();
        for (const ParamSpec& p : t->params) {
            nlohmann::json j = {{"name", p.name}, {"default", p.defaultValue}, {"min", p.min},
                                {"max", p.max},   {"integer", p.integer},      {"doc", p.doc}};
            if (!p.allowed.empty()) j["allowed"] = p.allowed;
            if (!p.names.empty()) j["names"] = p.names;  // value k is names[k]
            if (p.quality) j["quality"] = true;
            if (p.maxExclusive) j["max_exclusive"] = true;  // max itself is out of range
            if (!p.needs.empty()) j["needs"] = p.needs;     // "key=value" it needs
            params.push_back(j);
        }
        all.push_back({{"name", t->name},
                       {"family", t->family},
                       {"summary", t->summary},
                       {"parameters", params}});
    }
    return nlohmann::json({{"format_version", kTechniquesJsonFormat}, {"techniques", all}})
               .dump(2) +
           "\n";
}

}  // namespace

std::string techniquesListing(ListingFormat format) {
    return format == ListingFormat::Json       ? json()
           : format == ListingFormat::Markdown ? markdown()
                                               : text();
}

}  // namespace so
