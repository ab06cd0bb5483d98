#include "raster_compare/gl/technique_listing.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

#include "raster_compare/gl/denoisers/denoiser.h"
#include "raster_compare/gl/resolves/resolve.h"
#include "raster_compare/gl/shadow_maps/depth_bias.h"
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

// " (was `alpha`: history = 1 - alpha, until format 8)" for a renamed parameter.
std::string formerNote(const ParamSpec& p) {
    if (!p.former) return "";
    return " (was `" + p.former->name + "`" +
           (p.former->relation.empty() ? "" : ": " + p.former->relation) + ", until format " +
           std::to_string(p.former->untilFormat) + ")";
}

nlohmann::json provenanceJson(const Provenance& p) {
    nlohmann::json j = {{"anchor", p.anchor}, {"fidelity", fidelityName(p.fidelity)}};
    if (p.fidelity == Fidelity::Variant) j["deviations"] = p.deviations;
    return j;
}

// "**Provenance:** variant of <anchor>. Deviations: ..." for the Markdown and text listings.
std::string provenanceLine(const Provenance& p, const std::string& deviationIndent) {
    std::string s = p.fidelity == Fidelity::Faithful ? "faithful to " + p.anchor
                    : p.fidelity == Fidelity::Variant
                        ? "a variant of " + p.anchor + "; it differs:"
                        : "our own design (builds on " + p.anchor + ")";
    for (const std::string& d : p.deviations) s += "\n" + deviationIndent + d;
    return s;
}

// The named designs a method parameter's values are, one line each.
std::string namedValues(const ParamSpec& p, const std::string& indent) {
    std::string s;
    for (size_t k = 0; k < p.provenances.size() && k < p.names.size(); ++k)
        s += indent + "`" + p.name + "=" + p.names[k] +
             "`: " + provenanceLine(p.provenances[k], indent + "  - ") + "\n";
    return s;
}

// A technique's table leaves out the parameters of its axes' plug-ins, which are listed with the
// axis (ParamSpec::pluginParam), and says so once per axis: the axes whose plug-ins' parameters it
// has, by their parameter (the key its `needs` name: "bias" of "bias=slope|constant"), in order.
std::vector<std::string> pluginAxesOf(const ParamTable& params) {
    std::vector<std::string> axes;
    for (const ParamSpec& p : params) {
        if (!p.pluginParam) continue;
        const std::string axis = p.needs.substr(0, p.needs.find('='));
        if (std::find(axes.begin(), axes.end(), axis) == axes.end()) axes.push_back(axis);
    }
    return axes;
}

// Whose designs a method parameter's named values are, said beside the table, unless an axis's
// section says it.
bool listsNamedValues(const ParamSpec& p) {
    return !p.provenances.empty() && !p.pluginParam && p.name != "bias" && p.name != "denoiser" &&
           p.name != "resolve";
}

void markdownTable(std::ostringstream& o, const ParamTable& params) {
    o << "| parameter | default | range | meaning |\n|---|---|---|---|\n";
    for (const ParamSpec& p : params)
        if (!p.pluginParam)
            o << "| `" << p.name << "`" << (p.quality ? " (quality)" : "") << " | "
              << paramValueText(p, p.defaultValue) << " | " << range(p) << " | " << p.doc
              << formerNote(p) << " |\n";
    for (const std::string& axis : pluginAxesOf(params))
        o << "\nAnd the parameters of the " << axis << " it is given, each valid only with it: "
          << "[" << axis << " plug-ins](#" << axis << "-plug-ins).\n";
    bool named = false;
    for (const ParamSpec& p : params)
        if (listsNamedValues(p)) {
            o << (named ? "" : "\nIts named designs:\n\n") << namedValues(p, "- ");
            named = true;
        }
}

// One section per axis: its plug-ins, each with its summary and own table.
void markdownAxes(std::ostringstream& o, const std::vector<PluginAxis>& axes) {
    for (const PluginAxis& axis : axes) {
        o << "\n### " << axis.name << " plug-ins\n\nThe " << axis.family << " family's `"
          << axis.parameter << "=NAME` picks one; its parameters are valid "
          << "only with it.\n\n| " << axis.name << " | what it does |\n|---|---|\n";
        for (const AxisPlugin& p : axis.plugins)
            o << "| `" << p.name << "` | " << p.summary << " |\n";
        for (const AxisPlugin& p : axis.plugins) {
            o << "\n#### " << axis.name << " " << p.name << "\n\n"
              << p.summary << ".\n\n"
              << "**Provenance:** " << provenanceLine(p.provenance, "- ") << "\n\n";
            if (p.params.empty())
                o << "No parameters.\n";
            else
                markdownTable(o, p.params);
        }
    }
}

std::string markdown(const std::vector<PluginAxis>& axes) {
    std::ostringstream o;
    o << "| technique | family | fidelity | what it does |\n|---|---|---|---|\n";
    for (const TechniqueInfo* t : allTechniques())
        o << "| [`" << t->name << "`](#" << t->name << ") | " << t->family << " | "
          << fidelityName(t->provenance.fidelity) << " | " << t->summary << " |\n";
    for (const TechniqueInfo* t : allTechniques()) {
        o << "\n### " << t->name << "\n\n"
          << t->summary << " (" << t->family << ").\n\n"
          << "**Provenance:** " << provenanceLine(t->provenance, "- ") << "\n\n";
        if (t->alias)
            o << "A name for `" << aliasExpansion(*t) << "`: its parameters are that "
              << "technique's, under the names they had before the bias axis.\n\n";
        if (t->params.empty()) {
            o << "No parameters.\n";
            continue;
        }
        markdownTable(o, t->params);
    }
    markdownAxes(o, axes);
    return o.str();
}

void textTable(std::ostringstream& o, const ParamTable& params, const char* indent) {
    for (const ParamSpec& p : params)
        if (!p.pluginParam)
            o << indent << p.name << " = " << paramValueText(p, p.defaultValue) << "  [" << range(p)
              << "]  " << p.doc << formerNote(p) << "\n";
    for (const std::string& axis : pluginAxesOf(params))
        o << indent << "(and the parameters of the " << axis << " it is given: " << axis
          << " plug-ins, below)\n";
    for (const ParamSpec& p : params)
        if (listsNamedValues(p)) o << namedValues(p, indent);
}

std::string text(const std::vector<PluginAxis>& axes) {
    std::ostringstream o;
    for (const TechniqueInfo* t : allTechniques()) {
        o << t->name << " (" << t->family << "): " << t->summary
          << "\n    provenance: " << provenanceLine(t->provenance, "      - ") << "\n";
        textTable(o, t->params, "    ");
    }
    for (const PluginAxis& axis : axes) {
        o << "\n"
          << axis.name << " plug-ins (" << axis.family << ", " << axis.parameter << "=NAME):\n";
        for (const AxisPlugin& p : axis.plugins) {
            o << "  " << p.name << ": " << p.summary
              << "\n      provenance: " << provenanceLine(p.provenance, "        - ") << "\n";
            textTable(o, p.params, "      ");
        }
    }
    return o.str();
}

nlohmann::json jsonTable(const ParamTable& table) {
    nlohmann::json params = nlohmann::json::array();
    for (const ParamSpec& p : table) {
        nlohmann::json j = {{"name", p.name}, {"default", p.defaultValue}, {"min", p.min},
                            {"max", p.max},   {"integer", p.integer},      {"doc", p.doc}};
        if (!p.allowed.empty()) j["allowed"] = p.allowed;
        if (!p.names.empty()) j["names"] = p.names;  // value k is names[k]
        if (p.quality) j["quality"] = true;
        if (p.maxExclusive) j["max_exclusive"] = true;  // max itself is out of range
        if (!p.needs.empty()) j["needs"] = p.needs;     // "key=value" it needs
        if (p.former)  // the name it had, still accepted with a notice until that format
            j["former"] = {{"name", p.former->name},
                           {"relation", p.former->relation},
                           {"until_format", p.former->untilFormat}};
        for (const FormerValue& f : p.formerValues)  // a value's former name, still accepted
            j["former_values"].push_back(
                {{"name", f.name}, {"current", f.current}, {"until_format", f.untilFormat}});
        if (!p.provenances.empty()) {  // value k is the design provenances[k]
            j["provenances"] = nlohmann::json::array();
            for (const Provenance& v : p.provenances) j["provenances"].push_back(provenanceJson(v));
        }
        params.push_back(j);
    }
    return params;
}

std::string json(const std::vector<PluginAxis>& axes) {
    nlohmann::json all = nlohmann::json::array();
    for (const TechniqueInfo* t : allTechniques()) {
        nlohmann::json j = {{"name", t->name},
                            {"family", t->family},
                            {"summary", t->summary},
                            {"provenance", provenanceJson(t->provenance)},
                            {"parameters", jsonTable(t->params)}};
        if (t->alias) j["alias_of"] = aliasExpansion(*t);  // "basic:bias=slope"
        all.push_back(j);
    }
    nlohmann::json byName = nlohmann::json::object();
    for (const PluginAxis& axis : axes) {
        nlohmann::json plugins = nlohmann::json::array();
        for (const AxisPlugin& p : axis.plugins)
            plugins.push_back({{"name", p.name},
                               {"summary", p.summary},
                               {"provenance", provenanceJson(p.provenance)},
                               {"parameters", jsonTable(p.params)}});
        byName[axis.name] = {
            {"family", axis.family}, {"parameter", axis.parameter}, {"plugins", plugins}};
    }
    return nlohmann::json(
               {{"format_version", kTechniquesJsonFormat}, {"techniques", all}, {"axes", byName}})
               .dump(2) +
           "\n";
}

}  // namespace

std::vector<PluginAxis> registeredAxes() {
    return {biasAxis(), denoiserAxis(), resolveAxis()};
}

std::string techniquesListing(ListingFormat format, const std::vector<PluginAxis>& axes) {
    return format == ListingFormat::Json       ? json(axes)
           : format == ListingFormat::Markdown ? markdown(axes)
                                               : text(axes);
}

}  // namespace so
