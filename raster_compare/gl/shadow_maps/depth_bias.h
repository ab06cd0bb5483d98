// The shadow-map family's depth bias as an axis of plug-ins (issue 62): `bias=NAME` on every
// plain-map filter (basic, pcf, hw-pcf, pcss, the moment maps, cascades) picks how a receiver is
// kept from shadowing itself, independently of how the map is filtered: `pcf:bias=receiver-plane`,
// `pcss:bias=normal-offset`, `vsm:bias=slope`.
//
// Each bias lives in one file under biases/ (plus its GLSL file there) and registers itself in one
// line, at the start of a line in namespace so, found by CMake as techniques are:
//     SO_REGISTER_BIAS(SlopeDepthBias, "slope", "clamp(slope_factor tan(acos(n.l)), min, max)
//     texels");
// Its parameter table is the one source of its validation and docs: the filter's table carries
// every bias's parameters, each valid only with its bias (ParamSpec::needs "bias=NAME"), and a
// setting of a bias that is not chosen is an InputError, not silently ignored.
//
// The GLSL side (shaders/shadow_map.frag declares it; a bias's file defines it, after the frame):
//     struct BiasState { ... };                        // what the bias computes once per receiver
//     BiasState biasState(Receiver r, MapPoint m);      // m: where biasedPoint(r) falls in the map
//     vec3 biasedPoint(Receiver r);                     // where the receiver looks the map up
//     float biasedDepth(BiasState b, Receiver r, MapPoint m, vec2 o, float planeDepth);
// biasedDepth is the depth the filter compares with the map's texel o texels (need not be whole)
// from m's point, given the depth the filter puts the receiver at there (planeDepth: m.d for a
// flat lookup; pcss's receiver plane along the tap's ray). A bias that models the receiver's plane
// itself (receiver-plane, adaptive, oriented) computes its own depth at the tap's texel. The
// filter may define BIAS_SPREAD, how many texels its outer taps reach (the slope bias grows with
// it: pcf); 1 by default.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "raster_compare/gl/params.h"
#include "raster_compare/gl/plugin_axis.h"

namespace so {

class DepthBias {
  public:
    virtual ~DepthBias() = default;
    // Its GLSL file (shaders.h) and the #defines that configure it, for a map of `depthBits`.
    virtual const char* glsl() const = 0;
    virtual std::string defines(int /*depthBits*/) const { return ""; }
    // GL state for the map pass (polygon offset, culling), undone by endMapPass.
    virtual void beginMapPass() const {}
    virtual void endMapPass() const {}
};

struct BiasInfo {
    // Its number (Class::kNumber): the value of `bias` a setting may give instead of its name,
    // fixed once given, so a new bias never changes what an old number means.
    int number;
    std::string name, summary;
    ParamTable params;
    std::function<std::unique_ptr<DepthBias>(const ParamValues&)> create;
    Provenance provenance = {};  // Class::provenance() (provenance.h)
};

class BiasRegistry {
  public:
    // A name already there is std::invalid_argument (two files registering one name).
    void add(BiasInfo info);
    const std::vector<BiasInfo>& all() const { return all_; }

  private:
    std::vector<BiasInfo> all_;
};

// Generated (bias_list.cpp): calls soRegisterBias_<Class> of every registration line in
// biases/*.cpp, and how many lines there are.
void registerBuiltInBiases(BiasRegistry& registry);
extern const size_t kBuiltInBiasCount;

// Every registered bias by its number, the order of the `bias` parameter's names (a gap or a
// number taken twice is std::invalid_argument: a slip in the biases' code).
const std::vector<BiasInfo>& allBiases();
// The axis (plugin_axis.h), as `shadow-oracle techniques` lists it.
PluginAxis biasAxis();
// The `bias` parameter, defaulting to `defaultBias`, then every bias's parameters, each needing
// its bias (parameters that several biases share, with the same meaning, need any of them) and
// left out of the values while another bias is chosen (ParamSpec::pluginParam).
ParamTable biasAxisParams(const std::string& defaultBias);
// The bias the values chose (values of a table made with biasAxisParams).
std::unique_ptr<DepthBias> createDepthBias(const ParamValues& values);
// The bias's own name for the values' `bias` (for messages).
std::string biasName(const ParamValues& values);

#define SO_REGISTER_BIAS(Class, name, summary)                                             \
    void soRegisterBias_##Class(::so::BiasRegistry& registry) {                            \
        registry.add({Class::kNumber, name, summary, Class::params(),                      \
                      [](const ::so::ParamValues& v) -> std::unique_ptr<::so::DepthBias> { \
                          return std::make_unique<Class>(v);                               \
                      },                                                                   \
                      ::so::provenanceOf<Class>(0)});                                      \
    }                                                                                      \
    void soRegisterBias_##Class(::so::BiasRegistry& registry)

}  // namespace so
