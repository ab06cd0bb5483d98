// A denoiser of the ray-tracing family (techniques/raytraced.cpp, `denoiser=NAME`) as a plug-in.
//
// Each denoiser lives in one file here (plus its GLSL file) and registers itself in one line, at
// the start of a line in namespace so (after the file's anonymous namespace, which holds the
// class):
//     SO_REGISTER_DENOISER(Svgf, "svgf", "Schied et al. HPG 2017: temporal moments and ...");
// The line defines so::soRegisterDenoiser_Svgf; CMake finds the lines when it configures and
// generates denoiser_list.cpp (cmake/so_registry.cmake), as it does for techniques. The class
// gives its number (kNumber: its value as a number, `denoiser=2`, fixed once given, as settings
// and rows written before names give it), its parameter table (`static ParamTable params()`) and a
// constructor taking the technique's validated values. The `raytraced` technique's table is the
// `denoiser` parameter and the union of the denoisers' tables (plugin_axis.h), each parameter
// valid only with the denoisers that declare it.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "raster_compare/gl/denoisers/ray_frame.h"
#include "raster_compare/gl/params.h"
#include "raster_compare/gl/plugin_axis.h"

namespace so {

class PassClock;

// The family whose axis the denoisers are: the `raytraced` technique's.
inline constexpr const char* kRayTracingFamily = "ray tracing";

// One light's denoiser: its programs, made once, and its passes, run each frame.
class LightDenoiser {
  public:
    virtual ~LightDenoiser() = default;
    // Runs its passes over the frame's rays (RayFrame::raw), each timed with the clock under one
    // of Denoiser::passNames, and keeps what the next frame reads (RayFrame::keepHistory).
    // Returns the texture whose R holds the denoised V. Entered with the depth test off and the
    // G-buffer bound on units 1 and 2.
    virtual GLuint denoise(PassClock& clock) = 0;
    // Before the rays: how many of the technique's `spp` rays each pixel traces this frame (0 to
    // spp, in the G-buffer's order), decided from what frame f - 1 left; its passes timed under
    // the first Denoiser::passesBeforeTrace of passNames. Empty (the default): spp everywhere.
    // Entered as denoise is. Only an adaptive denoiser (rtg) overrides it.
    virtual std::vector<uint8_t> sampleCounts(PassClock& /*clock*/, int /*spp*/) { return {}; }
    // The GL memory of targets of its own (beyond RayFrame's).
    virtual uint64_t memoryBytes() const { return 0; }
};

// One setting's denoiser.
class Denoiser {
  public:
    virtual ~Denoiser() = default;
    // Its passes, in order, between the rays' "trace" and the light's "resolve", but for the
    // first passesBeforeTrace(), run before the trace (LightDenoiser::sampleCounts).
    virtual std::vector<std::string> passNames() const = 0;
    virtual size_t passesBeforeTrace() const { return 0; }
    // Whether its passes read the rays' mean distance to their blockers (raw's G).
    virtual bool needsHitDistance() const { return false; }
    // Whether it keeps a history across frames (RayFrame::keepHistory): a single frame is then a
    // cold start (Technique::buildsOverFrames).
    virtual bool keepsHistory() const { return true; }
    // The target its result lands in.
    virtual RayTarget result() const = 0;
    virtual std::unique_ptr<LightDenoiser> setUp(RayFrame& frame) const = 0;
};

struct DenoiserInfo {
    static constexpr const char* kKind = "denoiser";
    std::string name, summary;
    int number;  // its value as a number: `denoiser=<number>`
    ParamTable params;
    std::function<std::unique_ptr<Denoiser>(const ParamValues&)> create;
    Provenance provenance = {};  // Class::provenance() (provenance.h)
};

// Denoisers by number.
using DenoiserRegistry = NumberedRegistry<DenoiserInfo>;

// Generated (denoiser_list.cpp): calls soRegisterDenoiser_<Class> of every registration line in
// denoisers/*.cpp, and how many lines there are.
void registerBuiltInDenoisers(DenoiserRegistry& registry);
extern const size_t kBuiltInDenoiserCount;

// Every registered denoiser, by number: 0, 1, ... (a gap throws std::invalid_argument).
const std::vector<const DenoiserInfo*>& allDenoisers();
// The denoiser axis of the ray-tracing family: its plug-ins by number.
PluginAxis denoiserAxis();
// The denoiser that a `raytraced` setting's values pick (`denoiser`), made from those values.
std::unique_ptr<Denoiser> createDenoiser(const ParamValues& values);

// Parameters more than one denoiser takes: each is one spec, declared by every denoiser that reads
// it, so the family's table says which denoisers take it.
ParamSpec historyParam();         // the exponential history's weight (temporal, svgf, hitdist)
ParamSpec sigmaLuminanceParam();  // svgf's a-trous edge stops (hitdist's normal stop)
ParamSpec sigmaNormalParam();
ParamSpec sigmaDepthParam();

// Defines soRegisterDenoiser_<Class> (external linkage: at namespace so's scope). The trailing
// declaration takes the line's semicolon.
#define SO_REGISTER_DENOISER(Class, name, summary)                                        \
    void soRegisterDenoiser_##Class(::so::DenoiserRegistry& registry) {                   \
        registry.add({name, summary, Class::kNumber, Class::params(),                     \
                      [](const ::so::ParamValues& v) -> std::unique_ptr<::so::Denoiser> { \
                          return std::make_unique<Class>(v);                              \
                      },                                                                  \
                      ::so::provenanceOf<Class>(0)});                                     \
    }                                                                                     \
    void soRegisterDenoiser_##Class(::so::DenoiserRegistry& registry)

}  // namespace so
