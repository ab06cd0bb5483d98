// The lightmap family (docs/techniques.md, "Lightmaps"): per light, at set-up, the static meshes'
// shadows baked into an atlas (lightmap_atlas.h, lightmap_bake.h); per frame only a visibility
// pass that looks V up in it (shaders/lightmap.frag with the technique's filter,
// techniques/lightmap.glsl). The bake is not a frame: its time is the light's `bake_ms` in
// raster.json (with its passes' GL times under "bake.*"), never in a frame's. Meshes marked
// dynamic are neither baked nor shadowed: their shadows are missing, and raster.json counts them.
#pragma once

#include <memory>
#include <string>

#include "raster_compare/gl/lightmaps/lightmap_atlas.h"
#include "raster_compare/gl/lightmaps/lightmap_bake.h"
#include "raster_compare/gl/technique.h"

namespace so {

struct LightmapSettings {
    AtlasSettings atlas;
    BakeSettings bake;
    const char* glsl = nullptr;  // the technique's lookup: defines lightmapLookup
    std::string defines;         // configures it (the filter)
};

std::unique_ptr<LightTechnique> setUpLightmap(const LightmapSettings& settings,
                                              const LightSetup& setup);

}  // namespace so
