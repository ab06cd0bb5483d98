// An axis of a technique family: one of the family's parameters whose values are plug-ins (the
// ray-tracing family's `denoiser`), each plug-in with its own summary and parameter table. The
// family's technique takes the axis's method parameter and the union of the plug-ins' parameters,
// each valid only with the plug-ins that declare it (ParamSpec::needs, generated here, not written
// by hand); `shadow-oracle techniques` lists the axes with their plug-ins (technique_listing.h).
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "raster_compare/gl/params.h"

namespace so {

struct AxisPlugin {
    std::string name, summary;
    ParamTable params;
    Provenance provenance = {};  // whose design it is (provenance.h)
};

struct PluginAxis {
    std::string name;       // "denoiser"
    std::string family;     // the technique family it belongs to: "ray tracing"
    std::string parameter;  // the family's parameter that picks a plug-in: "denoiser"
    // By their numbers: value k of the parameter is plugins[k] (a setting may give the number).
    std::vector<AxisPlugin> plugins;
    // Former names of plug-ins, still accepted (ParamSpec::formerValues).
    std::vector<FormerValue> formerValues = {};
};

// The plug-ins of an axis by number (the denoisers, the resolves), as the generated list of their
// registration lines adds them; Info has `name`, `number` and `static constexpr const char* kKind`
// ("denoiser"), which the errors name.
template <class Info>
class NumberedRegistry {
  public:
    // A number or name already there is std::invalid_argument (two files registering one).
    void add(Info info) {
        for (const auto& [number, other] : byNumber_)
            if (other.name == info.name)
                throw std::invalid_argument(std::string(Info::kKind) + " \"" + info.name +
                                            "\" registered twice");
        const int number = info.number;
        const std::string name = info.name;
        if (!byNumber_.emplace(number, std::move(info)).second)
            throw std::invalid_argument(std::string(Info::kKind) + " \"" + name + "\": number " +
                                        std::to_string(number) + " taken by another");
    }
    const std::map<int, Info>& byNumber() const { return byNumber_; }
    // Every plug-in by number: 0, 1, ...; a gap is std::invalid_argument.
    std::vector<const Info*> inOrder() const {
        std::vector<const Info*> all;
        for (const auto& [number, info] : byNumber_) {
            if (number != int(all.size()))
                throw std::invalid_argument(std::string(Info::kKind) + " \"" + info.name +
                                            "\": number " + std::to_string(number) + ", expected " +
                                            std::to_string(all.size()) + " (no gaps)");
            all.push_back(&info);
        }
        return all;
    }

  private:
    std::map<int, Info> byNumber_;
};

// The parameter that picks a plug-in by name (methodParam over the plug-ins' names, each with its
// provenance), its default plugins[defaultIndex].
ParamSpec axisParam(const PluginAxis& axis, int defaultIndex, std::string doc);

// Every plug-in's parameters, once each, in the order the plug-ins first declare them; each needs
// "parameter=a|b" of the plug-ins that declare it, its doc is said as "a, b: <doc>", and it is a
// ParamSpec::pluginParam (a setting's values hold it only where one of those plug-ins is chosen;
// the listings give it with the axis). Plug-ins
// sharing a name must agree on its default, range and kind (else std::invalid_argument: a slip in
// their code).
ParamTable axisParams(const PluginAxis& axis);

}  // namespace so
