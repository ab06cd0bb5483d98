#include "raster_compare/gl/technique.h"

#include <algorithm>
#include <map>
#include <optional>
#include <stdexcept>
#include <utility>

#include "core/error.h"
#include "raster_compare/gl/resolves/resolve.h"

namespace so {

namespace {

// "key=value" as its key and value's text.
std::pair<std::string, std::string> splitSetting(const std::string& setting) {
    const size_t eq = setting.find('=');
    return {setting.substr(0, eq), eq == std::string::npos ? "" : setting.substr(eq + 1)};
}

// Whether spec.needs ("key=a|b") is met by the fixed setting of its key: true, false, or
// nothing when its key is not fixed.
std::optional<bool> needsMetBy(const ParamSpec& spec, const std::vector<std::string>& fixed) {
    if (spec.needs.empty()) return std::nullopt;
    const auto [key, values] = splitSetting(spec.needs);
    for (const std::string& f : fixed) {
        const auto [fixedKey, fixedValue] = splitSetting(f);
        if (fixedKey != key) continue;
        for (size_t from = 0;;) {
            const size_t bar = values.find('|', from);
            if (values.substr(from, bar == std::string::npos ? bar : bar - from) == fixedValue)
                return true;
            if (bar == std::string::npos) return false;
            from = bar + 1;
        }
    }
    return std::nullopt;
}

// An alias's table from its target's: the fixed parameters left out, those needing another
// choice of them dropped, those needing this one no longer needing it, and the old names kept.
ParamTable aliasTable(const TechniqueAlias& alias, const ParamTable& target) {
    ParamTable table;
    for (ParamSpec s : target) {
        bool fixedHere = false;
        for (const std::string& f : alias.fixed)
            fixedHere = fixedHere || splitSetting(f).first == s.name;
        const std::optional<bool> met = needsMetBy(s, alias.fixed);
        if (fixedHere || met == false) continue;
        if (met == true) s.needs.clear(), s.pluginParam = false;
        for (const auto& [old, current] : alias.renames)
            if (s.name == current) s.name = old;
        table.push_back(std::move(s));
    }
    return table;
}

// The named design a fixed setting ("bias=receiver-plane") or a value chooses, if its parameter's
// values are named designs.
std::optional<ProvenancePart> chosenPart(const ParamSpec& spec, double value) {
    const size_t k = size_t(value);
    if (spec.provenances.empty() || value < 0 || k >= spec.provenances.size() ||
        k >= spec.names.size())
        return std::nullopt;
    return ProvenancePart{spec.name + "=" + spec.names[k], spec.provenances[k]};
}

// An alias's target and what its fixed settings choose.
std::vector<ProvenancePart> aliasParts(const TechniqueAlias& alias, const TechniqueInfo& target) {
    std::vector<ProvenancePart> parts = {{"technique " + target.name, target.provenance}};
    for (const std::string& f : alias.fixed) {
        const auto [key, value] = splitSetting(f);
        for (const ParamSpec& s : target.params) {
            if (s.name != key) continue;
            for (size_t k = 0; k < s.names.size(); ++k)
                if (s.names[k] == value)
                    if (auto part = chosenPart(s, double(k))) parts.push_back(*part);
        }
    }
    return parts;
}

// Fills in every alias's family, table and create from its target (an alias of an alias, or of
// a name not registered, is a slip in the code: std::invalid_argument).
void resolveAliases(std::map<std::string, TechniqueInfo>& byName) {
    for (auto& [name, info] : byName) {
        if (!info.alias) continue;
        const auto target = byName.find(info.alias->target);
        if (target == byName.end() || target->second.alias)
            throw std::invalid_argument("technique alias \"" + name + "\": no technique \"" +
                                        info.alias->target + "\"");
        info.family = target->second.family;
        info.params = aliasTable(*info.alias, target->second.params);
        info.create = target->second.create;
        info.provenance = combinedProvenance(aliasParts(*info.alias, target->second));
    }
}

// Built on first use from the generated list (thread-safe: a function-local static). Never
// modified afterwards, so the pointers allTechniques hands out stay valid.
const std::map<std::string, TechniqueInfo>& registry() {
    static const std::map<std::string, TechniqueInfo> r = [] {
        TechniqueRegistry built;
        registerBuiltInTechniques(built);
        std::map<std::string, TechniqueInfo> byName = built.byName();
        resolveAliases(byName);
        return byName;
    }();
    return r;
}

}  // namespace

void TechniqueRegistry::add(TechniqueInfo info) {
    const std::string name = info.name;
    if (!byName_.emplace(name, std::move(info)).second)
        throw std::invalid_argument("technique \"" + printable(name) + "\" registered twice");
}

std::vector<const TechniqueInfo*> allTechniques() {
    std::vector<const TechniqueInfo*> all;
    for (const auto& [name, info] : registry()) all.push_back(&info);
    std::stable_sort(all.begin(), all.end(), [](const TechniqueInfo* a, const TechniqueInfo* b) {
        return a->family < b->family;
    });
    return all;
}

const TechniqueInfo& findTechnique(const std::string& name) {
    const auto it = registry().find(name);
    if (it != registry().end()) return it->second;
    // Names that claimed a source they did not follow (issue 63): said, not just listed.
    static const std::map<std::string, std::string> renamed = {
        {"oriented-bias",
         "half-texel-bias (basic:bias=half-texel): the FFXVI talk it claimed "
         "was never read, so it is a design of our own"}};
    if (const auto r = renamed.find(name); r != renamed.end())
        throwInputError("technique", "name", "technique \"" + name + "\" is now " + r->second);
    std::string valid;
    for (const TechniqueInfo* t : allTechniques()) valid += (valid.empty() ? "" : ", ") + t->name;
    throwInputError("technique", "name",
                    "unknown technique \"" + printable(name, 40) + "\" (valid: " + valid + ")");
}

std::string aliasExpansion(const TechniqueInfo& info) {
    if (!info.alias) return "";
    std::string s = info.alias->target;
    for (size_t i = 0; i < info.alias->fixed.size(); ++i)
        s += (i ? "," : ":") + info.alias->fixed[i];
    return s;
}

std::vector<ProvenancePart> provenanceParts(const Technique& technique) {
    const TechniqueInfo& info = findTechnique(technique.name());
    std::vector<ProvenancePart> parts =
        info.alias ? aliasParts(*info.alias, findTechnique(info.alias->target))
                   : std::vector<ProvenancePart>{{"technique " + info.name, info.provenance}};
    const ParamValues& values = technique.values();
    for (const ParamSpec& spec : info.params)
        if (values.all().count(spec.name) && needsMet(spec, info.params, values))
            if (auto part = chosenPart(spec, values.real(spec.name))) parts.push_back(*part);
    return parts;
}

std::unique_ptr<Technique> createTechnique(const std::string& name,
                                           const std::vector<std::string>& settings) {
    const TechniqueInfo& info = findTechnique(name);
    if (!info.alias) {
        std::unique_ptr<Technique> t = info.create(parseParams(info.name, info.params, settings));
        t->name_ = info.name;
        return t;
    }
    // Checked against the alias's own table first, so that errors name its keys; then its
    // settings under the target's names, with the fixed ones. Its values, which raster.json and
    // metrics.json list, are under its own names (bias:bias=2, not depth_texels), as its table.
    ParamValues own = parseParams(info.name, info.params, settings);
    std::vector<std::string> expanded = info.alias->fixed;
    for (const std::string& setting : settings) {
        auto [key, value] = splitSetting(setting);
        for (const auto& [old, current] : info.alias->renames)
            if (key == old) key = current;
        expanded.push_back(key + "=" + value);
    }
    const TechniqueInfo& target = findTechnique(info.alias->target);
    std::unique_ptr<Technique> t = target.create(parseParams(info.name, target.params, expanded));
    t->name_ = info.name;
    t->values_ = std::move(own);
    return t;
}

bool Technique::buildsOverFrames() const {
    const Resolve* r = resolve();
    return r && !r->passNames().empty();  // resolve=none keeps nothing
}

}  // namespace so
