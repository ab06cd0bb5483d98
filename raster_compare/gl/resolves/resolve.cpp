#include "raster_compare/gl/resolves/resolve.h"

#include <stdexcept>

#include "core/error.h"

namespace so {

namespace {

// Built on first use from the generated list (a function-local static), never modified after.
const std::vector<const ResolveInfo*>& registry() {
    static const ResolveRegistry r = [] {
        ResolveRegistry built;
        registerBuiltInResolves(built);
        return built;
    }();
    static const std::vector<const ResolveInfo*> byNumber = r.inOrder();
    return byNumber;
}

}  // namespace

const std::vector<const ResolveInfo*>& allResolves() {
    return registry();
}

PluginAxis resolveAxis() {
    PluginAxis axis{"resolve", "shadow map", "resolve", {}};
    for (const ResolveInfo* r : allResolves())
        axis.plugins.push_back({r->name, r->summary, r->params, r->provenance});
    return axis;
}

std::unique_ptr<Resolve> createResolve(const ParamValues& values) {
    // parseParams held the number to the method parameter's range: one per resolve.
    const ResolveInfo* info = allResolves().at(size_t(values.integer("resolve")));
    std::unique_ptr<Resolve> r = info->create(values);
    r->name_ = info->name;
    return r;
}

}  // namespace so
