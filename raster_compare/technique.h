// The shadow-map techniques behind one small interface (docs/techniques.md). Each technique lives
// in one file under techniques/ with its parameter table and defaults at the top; the shader code
// is shared (shaders/visibility.frag) and a technique chooses its variant by #defines.
//
// Lengths in parameters are in texels: multiples of the world-space size of one shadow-map texel
// at the receiver, so the same setting means the same thing at any scene scale or resolution.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

namespace so {

struct ParamSpec {
    std::string name;
    double defaultValue;
    double min, max;
    bool integer;
    std::string doc;
};

// Parameter values after validation: every parameter of the technique, defaults filled in.
using ParamValues = std::map<std::string, double>;

class ShadowTechnique {
  public:
    virtual ~ShadowTechnique() = default;
    virtual std::string name() const = 0;
    virtual std::string summary() const = 0;
    // The technique's own parameters (the common ones, resolution and depth_format, are added).
    virtual std::vector<ParamSpec> ownParams() const = 0;
    // #defines for the visibility shader.
    virtual std::string shaderDefines(const ParamValues& p) const = 0;
    // GL state for the shadow-map pass (polygon offset, culling); called with the pass bound.
    virtual void beginShadowPass(const ParamValues&) const {}
    virtual void endShadowPass(const ParamValues&) const {}
    // Filtered techniques (vsm, esm, evsm) render moments instead of a depth map, blurred by a
    // separable Gaussian of this radius in texels (0: none).
    virtual bool filtered() const { return false; }
    // The map is sampled with the hardware depth compare and GL_LINEAR filtering.
    virtual bool hardwareCompare() const { return false; }
    virtual int blurRadius(const ParamValues&) const { return 0; }
    // The moments of the far plane (t = 1), which the moment map is cleared to.
    virtual std::array<float, 4> farMoments(const ParamValues&) const { return {1, 1, 0, 0}; }

    std::vector<ParamSpec> params() const;
    // Parses "key=value" settings; unknown keys and out-of-range values are InputErrors naming
    // the valid keys and the range.
    ParamValues parse(const std::vector<std::string>& settings) const;
};

// The slope-scaled bias shared by slope-bias, pcf and hw-pcf: its parameters (alpha, min, max,
// in texels) and its #defines.
std::vector<ParamSpec> slopeBiasParams();
std::string slopeBiasDefines(const ParamValues& p);

const std::vector<const ShadowTechnique*>& allTechniques();
// Throws InputError listing the valid names.
const ShadowTechnique& findTechnique(const std::string& name);

// The technique files register through these.
const ShadowTechnique& basicTechnique();
const ShadowTechnique& biasTechnique();
const ShadowTechnique& slopeBiasTechnique();
const ShadowTechnique& polygonOffsetTechnique();
const ShadowTechnique& normalOffsetTechnique();
const ShadowTechnique& pcfTechnique();
const ShadowTechnique& backFacesTechnique();
const ShadowTechnique& hwPcfTechnique();
const ShadowTechnique& vsmTechnique();
const ShadowTechnique& esmTechnique();
const ShadowTechnique& evsmTechnique();

}  // namespace so
