#include "raster_compare/gl/technique.h"

#include <algorithm>
#include <map>

#include "core/error.h"

namespace so {

namespace {
// Built on first use, so registration from other files' static initialisers is safe in any order.
std::map<std::string, TechniqueInfo>& registry() {
    static std::map<std::string, TechniqueInfo> r;
    return r;
}
}  // namespace

bool registerTechnique(TechniqueInfo info) {
    const std::string name = info.name;
    const bool added = registry().emplace(name, std::move(info)).second;
    SO_CHECK(added);
    return added;
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
    throwInputError("command line", "--technique",
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
