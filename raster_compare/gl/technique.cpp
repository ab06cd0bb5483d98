#include "raster_compare/gl/technique.h"

#include <algorithm>
#include <map>
#include <stdexcept>

#include "core/error.h"

namespace so {

namespace {

// Built on first use from the generated list (thread-safe: a function-local static). Never
// modified afterwards, so the pointers allTechniques hands out stay valid.
const std::map<std::string, TechniqueInfo>& registry() {
    static const TechniqueRegistry r = [] {
        TechniqueRegistry built;
        registerBuiltInTechniques(built);
        return built;
    }();
    return r.byName();
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
    std::string valid;
    for (const TechniqueInfo* t : allTechniques()) valid += (valid.empty() ? "" : ", ") + t->name;
    throwInputError("technique", "name",
                    "unknown technique \"" + printable(name, 40) + "\" (valid: " + valid + ")");
}

std::unique_ptr<Technique> createTechnique(const std::string& name,
                                           const std::vector<std::string>& settings) {
    const TechniqueInfo& info = findTechnique(name);
    std::unique_ptr<Technique> t = info.create(parseParams(info.name, info.params, settings));
    t->name_ = info.name;
    return t;
}

}  // namespace so
