// How a frame is resolved over time (`resolve=NAME`, docs/techniques.md#resolve): a plug-in axis
// of the techniques whose taps turn every frame (temporal=on of pcf, pcss and smrt, and the
// engines' own turning patterns). After a light's visibility pass, the light's resolve runs its
// passes on the GPU (timed and counted with the technique's), reads what the frame before left in
// the caller's TemporalState (time/temporal_state.h), reprojected through the camera's and every
// mesh's exact motion, and leaves the resolved V in the light's target; after the frame it keeps
// what the next frame reads.
//
// Each resolve lives in one file here (plus its GLSL file) and registers itself in one line, at
// the start of a line in namespace so (after the file's anonymous namespace):
//     SO_REGISTER_RESOLVE(Taa, "taa", "Bevy's TAA of the lit image ...");
// CMake generates resolve_list.cpp from those lines (cmake/so_registry.cmake), as it does for
// techniques and denoisers. The class gives its number (kNumber, fixed once given), its parameter
// table (`static ParamTable params()`), its provenance and a constructor taking the technique's
// validated values.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "raster_compare/gl/params.h"
#include "raster_compare/gl/plugin_axis.h"

namespace so {

struct Light;
class GpuScene;
class CameraPass;
class LightTarget;
class PassClock;
class TemporalState;

// What a resolve gets to set up one light of one technique's render.
struct ResolveSetup {
    const Light& light;
    const GpuScene& scene;
    const CameraPass& camera;  // jittered where the resolve asked for it (jitterPixels)
    const LightTarget& target;
    TemporalState* state = nullptr;  // null: a cold start, no history read or kept
    const void* owner = nullptr;     // the technique: whose history it is in the state
};

// One light's resolve: its programs and targets, made once per render.
class LightResolve {
  public:
    virtual ~LightResolve() = default;
    // After the light's visibility pass: reads the target's V, writes the resolved V back into it.
    // Entered with the light's target bound and depth test EQUAL; leaves that state.
    virtual void resolve(PassClock& clock) = 0;
    // After the frame's renders: keeps what the next frame reads in the state (nothing without).
    virtual void keep() = 0;
    // How many frames the last resolved V holds (this one included); 0: a cold start.
    virtual int historyFrames() const = 0;
    virtual uint64_t memoryBytes() const = 0;
};

// One setting's resolve.
class Resolve {
  public:
    virtual ~Resolve() = default;
    const std::string& name() const { return name_; }
    // Its passes, in order, after the visibility pass; none: nothing runs.
    virtual std::vector<std::string> passNames() const = 0;
    // The camera's sub-pixel offset for frame `frameIndex`, in pixels ((0, 0): none).
    virtual glm::dvec2 jitterPixels(int /*frameIndex*/) const { return {0.0, 0.0}; }
    // Null where it runs no pass (none).
    virtual std::unique_ptr<LightResolve> setUp(const ResolveSetup& setup) const = 0;

  private:
    friend std::unique_ptr<Resolve> createResolve(const ParamValues& values);
    std::string name_;
};

struct ResolveInfo {
    static constexpr const char* kKind = "resolve";
    std::string name, summary;
    int number;
    ParamTable params;
    std::function<std::unique_ptr<Resolve>(const ParamValues&)> create;
    Provenance provenance = {};
};

using ResolveRegistry = NumberedRegistry<ResolveInfo>;

// Generated (resolve_list.cpp).
void registerBuiltInResolves(ResolveRegistry& registry);
extern const size_t kBuiltInResolveCount;

// Every registered resolve, by number (a gap throws std::invalid_argument).
const std::vector<const ResolveInfo*>& allResolves();
// The resolve axis: its plug-ins by number.
PluginAxis resolveAxis();
// The resolve a setting's values pick (`resolve`), made from those values.
std::unique_ptr<Resolve> createResolve(const ParamValues& values);

#define SO_REGISTER_RESOLVE(Class, name, summary)                                        \
    void soRegisterResolve_##Class(::so::ResolveRegistry& registry) {                    \
        registry.add({name, summary, Class::kNumber, Class::params(),                    \
                      [](const ::so::ParamValues& v) -> std::unique_ptr<::so::Resolve> { \
                          return std::make_unique<Class>(v);                             \
                      },                                                                 \
                      ::so::provenanceOf<Class>(0)});                                    \
    }                                                                                    \
    void soRegisterResolve_##Class(::so::ResolveRegistry& registry)

}  // namespace so
