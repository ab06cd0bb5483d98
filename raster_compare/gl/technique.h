// A shadow technique, of any family, as a typed plug-in (docs/techniques.md, CONTRIBUTING.md).
//
// Each technique lives in one file under techniques/ (plus its GLSL file there) and registers
// itself in one line, at the start of a line in namespace so (after the file's anonymous
// namespace, which holds the class):
//     SO_REGISTER_TECHNIQUE(Pcf, "pcf", "NxN grid percentage-closer filtering, compare per tap");
// The line defines so::soRegister_Pcf; CMake finds the lines when it configures and generates
// technique_list.cpp, which calls every such function (registerBuiltInTechniques). The registry
// builds itself from that list on first use, so a program linking the static so_raster names, and
// therefore keeps, every technique: nothing depends on static initialisers a linker may drop.
// The class gives its parameter table (`static ParamTable params()`) and a constructor that takes
// the validated values and keeps them as typed members: the registry's `create` parses the
// settings against the table, then constructs. Validation lives in the constructor, not in the
// shader setup, so a bad setting fails before any GL work.
//
// At render time a technique sets up, per light, an object that owns that light's passes
// (LightTechnique): passes that see only the light (a shadow map) run before the camera pass, and
// the visibility pass writes the light's V into the shared frame after it (renderer.h).
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/scene.h"
#include "raster_compare/gl/params.h"
#include "raster_compare/gl/render/raster_result.h"

namespace so {

class GpuScene;
class CameraPass;
class PassClock;
class Resolve;
class TemporalState;

// What one light's set-up made that another instance of the same technique may take over in the
// same render: the counted frame's instance and the timed one (renderer.cpp) share the lightmap's
// bake this way. Keyed as the technique chooses (the light's name: names are unique in a scene).
struct SetUpShared {
    virtual ~SetUpShared() = default;
};
using SetUpShares = std::map<std::string, std::shared_ptr<const SetUpShared>>;

// What a technique gets to set up one light.
struct LightSetup {
    const Light& light;
    const GpuScene& scene;
    const CameraPass& camera;
    // The local-frame bounds of the receivers the camera sees, when the technique asked for them
    // (Technique::needsReceiverBounds).
    const std::optional<Bounds3d>& lsReceivers;
    // Where the set-ups of one technique in one render leave and find what they share; null: none.
    SetUpShares* shared = nullptr;
    // The depth probe (docs/exr-channels.md) is wanted where the technique can give it: outside
    // the counted frame (the probe is a diagnostic, no part of a technique's work). The light's
    // target then has one if the technique probesDepth().
    bool depthProbe = false;
    // The frame's index (RasterOptions::frameIndex): what techniques with temporal=on turn
    // their taps by (u_frameIndex); 0 for a single frame.
    int frameIndex = 0;
    // The caller's temporal state (time/temporal_state.h), where a technique keeps what it builds
    // over frames (the ray-traced denoisers' history); null: a cold start.
    TemporalState* temporal = nullptr;
};

class LightTarget;

// What a shadow-map technique's own depth comparison saw per pixel (docs/exr-channels.md), top
// row first, in the scene's local units, for classing acne by its cause (docs/metrics.md).
struct DepthComparison {
    // RGBA per pixel: the depth the map held at the receiver's own texel (+inf beyond the map),
    // the receiver's own light-space depth, one map texel's size there, 0; -1, -1, 0, 0 where
    // nothing was compared.
    std::vector<float> probe;
    // Where a screen-space pass filters V after the comparison (blur): the comparison's own V;
    // empty otherwise (V is the comparison's).
    std::vector<float> unfilteredVisibility;
};

// One light's GL objects and passes. Made by Technique::setUp with a current context. Each pass
// it runs is timed with the clock under one of the names passNames() lists (raster.json).
class LightTechnique {
  public:
    virtual ~LightTechnique() = default;
    // The passes it runs for the light, in order: {"shadow_map", "visibility"}, ...
    virtual std::vector<std::string> passNames() const = 0;
    // Passes before the camera pass (shadow maps); GL state is the frame's (depth test on, depth
    // writes on, clip control 0..1) and must be left so.
    virtual void renderLightPasses(PassClock& clock) = 0;
    // After the camera pass: the light's target is bound, its colours cleared, the camera pass's
    // depth and stencil attached (the stencil's content undefined), depth writes off and depth
    // test EQUAL. Ends with the scene drawn so: location 0 gets V, location 1 the predicted
    // aliasing, location 2 (where the target has a depth probe) what the comparison saw; any
    // other state it changes it restores.
    virtual void renderVisibility(PassClock& clock) = 0;
    // Switches its visibility pass to the program that also writes the depth probe (on) or back
    // (off); returns whether it has one. The renderer probes in one untimed frame after the timed
    // ones, so the probe costs no frame time.
    virtual bool probeDepth(bool /*on*/) { return false; }
    // After the probed frame: what its own depth comparison saw, read from the light's target `own`
    // (or a target of its own); none for techniques that compare no depth map.
    virtual std::optional<DepthComparison> readDepthComparison(const LightTarget& /*own*/) const {
        return std::nullopt;
    }
    // The light's camera and map, and the technique's own counts, for raster.json (the light's
    // name and type, the family, the passes, timings and memory are filled in by the renderer).
    virtual RasterLightStats describe() const = 0;
    // The GL memory it holds (maps and intermediate targets), from the formats and sizes.
    virtual uint64_t memoryBytes() const = 0;
};

class Technique {
  public:
    explicit Technique(const ParamValues& values) : values_(values) {}
    virtual ~Technique() = default;
    Technique(const Technique&) = delete;
    Technique& operator=(const Technique&) = delete;

    const std::string& name() const { return name_; }
    // Every parameter with its value, defaults included (for raster.json and metrics.json); an
    // alias's under its own table's names. The parameters of an axis's plug-ins that were not
    // chosen are left out (ParamSpec::pluginParam).
    const ParamValues& values() const { return values_; }
    // V is a filtered estimate (moments), so light bleeding is measured (docs/metrics.md).
    virtual bool filtered() const { return false; }
    // Asks the renderer for the receivers the camera sees before setUp.
    virtual bool needsReceiverBounds() const { return false; }
    // Its visibility pass can write what its own depth comparison saw into the light's target
    // (location 2), when LightSetup::depthProbe asks (LightTechnique::probeDepth).
    virtual bool probesDepth() const { return false; }
    // How its frames are resolved over time (temporal=on: resolves/resolve.h, `resolve=NAME`);
    // null where every frame stands alone.
    virtual const Resolve* resolve() const { return nullptr; }
    // Whether its V depends on the frames before (a resolve that keeps a history, a denoiser's):
    // such a row says how many frames built it (metrics.json's history_frames, docs/metrics.md),
    // 0 for a single-frame compare (a cold start).
    virtual bool buildsOverFrames() const;
    virtual std::unique_ptr<LightTechnique> setUp(const LightSetup& setup) const = 0;

  private:
    friend std::unique_ptr<Technique> createTechnique(const std::string&,
                                                      const std::vector<std::string>&);
    std::string name_;
    ParamValues values_;
};

// A name for a technique with some of its settings fixed: the bias techniques are the one-tap
// filter with a bias (slope-bias = basic:bias=slope, receiver-plane = basic:bias=receiver-plane),
// kept as names so that every setting, spec and baseline that uses them still runs and gives the
// same numbers. Its table is the target's without the fixed parameters and without those that only
// another choice of them uses; `renames` keeps the names its parameters had before they moved into
// the target's axis (`bias:bias=2` is `basic:bias=constant,depth_texels=2`).
struct TechniqueAlias {
    std::string target;                                        // "basic"
    std::vector<std::string> fixed;                            // {"bias=constant"}
    std::vector<std::pair<std::string, std::string>> renames;  // {its name, the target's}
};

struct TechniqueInfo {
    std::string name, summary, family;
    ParamTable params;
    std::function<std::unique_ptr<Technique>(const ParamValues&)> create;
    // An alias's expansion; its create is the target's, given the target's values.
    std::optional<TechniqueAlias> alias = {};
    // Whose design it is (Class::provenance(), provenance.h); an alias's is its target's with the
    // plug-ins its fixed settings choose (combinedProvenance).
    Provenance provenance = {};
};

// Techniques by name.
class TechniqueRegistry {
  public:
    // A name already there is std::invalid_argument (two files registering one name).
    void add(TechniqueInfo info);
    const std::map<std::string, TechniqueInfo>& byName() const { return byName_; }

  private:
    std::map<std::string, TechniqueInfo> byName_;
};

// Generated (technique_list.cpp): calls soRegister_<Class> of every registration line in
// techniques/*.cpp (SO_REGISTER_TECHNIQUE and SO_REGISTER_TECHNIQUE_ALIAS), and how many lines
// there are.
void registerBuiltInTechniques(TechniqueRegistry& registry);
extern const size_t kBuiltInTechniqueCount;

// Its expansion: "basic:bias=slope" for slope-bias; empty for a technique that is no alias.
std::string aliasExpansion(const TechniqueInfo& info);

// Whose designs a technique's setting grades: the technique's (an alias's target's) and, for every
// method parameter whose values are named designs (the bias and denoiser axes, pattern=three),
// the chosen value's, where its `needs` are met (provenance.h). Reports mark a row whose
// combinedFidelity is not faithful.
std::vector<ProvenancePart> provenanceParts(const Technique& technique);

// Every registered technique, by family and then name. The first call builds the registry (a
// duplicate name throws std::invalid_argument here, and again on every later call).
std::vector<const TechniqueInfo*> allTechniques();
// An unknown name throws InputError (file "technique", field "name") listing the valid names.
const TechniqueInfo& findTechnique(const std::string& name);
// Finds, parses the settings ("key=value") against the table and constructs: every user error is
// an InputError naming the technique and the key.
std::unique_ptr<Technique> createTechnique(const std::string& name,
                                           const std::vector<std::string>& settings);

// Defines soRegister_<Class> (external linkage: at namespace so's scope, not in an anonymous
// namespace, else the generated list fails to link). The trailing declaration takes the line's
// semicolon. Class::kFamily is the family's name as listed: "shadow map", ...
#define SO_REGISTER_TECHNIQUE(Class, name, summary)                                        \
    void soRegister_##Class(::so::TechniqueRegistry& registry) {                           \
        registry.add({name, summary, Class::kFamily, Class::params(),                      \
                      [](const ::so::ParamValues& v) -> std::unique_ptr<::so::Technique> { \
                          return std::make_unique<Class>(v);                               \
                      },                                                                   \
                      std::nullopt, ::so::provenanceOf<Class>(0)});                        \
    }                                                                                      \
    void soRegister_##Class(::so::TechniqueRegistry& registry)

// An alias (TechniqueAlias): SO_REGISTER_TECHNIQUE_ALIAS(Id, "slope-bias", "summary", "basic",
// {"bias=slope"}, {}); its table and create are the target's, made when the registry is built.
#define SO_REGISTER_TECHNIQUE_ALIAS(Id, name, summary, ...)                           \
    void soRegister_##Id(::so::TechniqueRegistry& registry) {                         \
        registry.add({name, summary, "", {}, {}, ::so::TechniqueAlias{__VA_ARGS__}}); \
    }                                                                                 \
    void soRegister_##Id(::so::TechniqueRegistry& registry)

}  // namespace so
