// The adaptive (virtual) shadow map's per-light passes, shared by the techniques that look points
// up in its pages: `adaptive` (techniques/adaptive.cpp: one depth test per receiver) and `smrt`
// with map=adaptive (techniques/smrt.cpp: rays marched through the pages). The passes are
// adaptive.cpp's header's (mark, pages, refine, visibility); the technique gives the visibility
// frame. The page bookkeeping is virtual_shadow_map.h's.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "raster_compare/gl/params.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"
#include "raster_compare/gl/shadow_maps/virtual_shadow_map.h"
#include "raster_compare/gl/technique.h"

namespace so {

// The virtual map's own parameters, read once.
struct VirtualMapSettings {
    // virtual_size, page_size, pool_mb (the table's quality parameter when `poolIsQuality`),
    // density, refine; each needing `needs` (ParamSpec::needs) where that is not empty.
    static ParamTable params(const std::string& needs = {}, bool poolIsQuality = true);
    // A page larger than the map, or a pool that holds no page: InputErrors naming
    // "technique <technique>" and the field.
    VirtualMapSettings(const ParamValues& values, const std::string& technique);

    std::string technique;  // for error messages
    VirtualMapLayout layout;
    int poolMb;
    int poolColumns, poolRows;  // the largest about square grid of pages within pool_mb
    double density;
    bool refine;

    int poolPages() const { return poolColumns * poolRows; }
    // The side of the cube map of 32-bit depth that point and area lights fall back to: six
    // faces in (about) the pool's memory.
    int cubeResolution() const;
};

// What a technique draws over the pages in the visibility pass.
struct VirtualVisibility {
    // The frame: after alpha_test.glsl, techniques/adaptive.glsl and `includes`; writes V at
    // location 0 and the predicted aliasing at location 1 (shaders/adaptive_visibility.frag).
    const char* frag = nullptr;
    std::vector<const char*> includes;
    std::string defines;  // beyond adaptive.glsl's own
    // Uniforms of the visibility program that depend on the light or the frame; may be empty.
    std::function<void(GLuint program, const LightSetup& setup)> setUniforms;
};

// "key=value" with the value's every digit: a setting for the fallback's technique.
std::string settingText(const std::string& key, double value);

// Makes the technique that point and area lights fall back to, given the cube map's side.
using CubeFallback = std::function<std::unique_ptr<Technique>(int cubeResolution)>;

// One light: directional and spot lights get the virtual map (passes mark, pages, refine,
// visibility); point and area lights `fallback`'s technique on a cube map of
// settings.cubeResolution() (its own passes; counts cube_fallback = 1 and cube_resolution), set
// up with the depth probe when `fallbackProbes` (the owner's target has one). `settings`, `bias`
// must outlive the light.
std::unique_ptr<LightTechnique> setUpVirtualShadowMap(
    const VirtualMapSettings& settings, const SlopeBias& bias, VirtualVisibility visibility,
    const LightSetup& setup, const CubeFallback& fallback, bool fallbackProbes);

}  // namespace so
