// The lightmap's bake (docs/techniques.md, "Lightmaps"): one light's V at every texel of the atlas,
// computed by the raster path as an engine's baker would, never by the oracle:
//   1. the static triangles rasterised in the atlas's space (gl_Position = texel / size * 2 - 1,
//      shaders/lightmap_bake.vert), each covered texel's surface point and normal kept
//      ("bake.texels", shaders/lightmap_texels.frag), then each triangle's centroid drawn as a
//      point where no triangle covered that texel's centre: every triangle gets a texel, even one
//      smaller than a texel or a sliver that covers no centre;
//   2. per point of the light (the light itself, or `samples` points of an area light when the
//      scene asks for penumbrae, light_samples.h): a shadow map of the static meshes at
//      `resolution` (cube maps for points, "bake.shadow_map"), its depth test at every texel
//      (shaders/shadow_map.frag with slope-bias's lookup at its defaults, "bake.visibility"), and
//      that sample's V added with accumulate's weight G = cos cos / r^2
//      (techniques/accumulate.glsl, "bake.weights"), so the bake's limit is the oracle's V;
//   3. V = sum(G v) / sum(G), then `dilate` passes that fill each empty texel next to filled ones
//      with their mean ("bake.dilate"; llvmpipe has no conservative rasterisation, so a texel a
//      triangle covers only partly is empty, and a filter reading it would show a seam), and V
//      stored as GL_R8 ("bake.store").
// Meshes marked dynamic are in neither the atlas nor the shadow maps: their shadows are left out.
// The passes' GL times are kept under the names above, apart from any frame's.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "core/scene.h"
#include "raster_compare/gl/context/gl_object.h"
#include "raster_compare/gl/lightmaps/lightmap_atlas.h"

namespace so {

class GpuScene;

struct BakeSettings {
    int resolution = 2048;  // the shadow map's side (cube maps: per face)
    int samples = 64;       // area lights, when the scene's effects include "penumbra"
    int dilate = 2;         // passes of dilation
};

struct BakedLightmap {
    GlTexture atlas;             // GL_R8, the atlas's size: V per texel
    int samples = 0;             // points of the light baked
    uint64_t texelsCovered = 0;  // texels whose centre a triangle covers
    // More: the texel of a triangle's centroid, where no triangle covered its centre.
    uint64_t texelsFromCentroids = 0;
    uint64_t texelsFilled = 0;             // all filled after dilation
    std::map<std::string, double> passMs;  // GL time of each bake pass, summed over the samples
    // The bake's largest GL memory at once (its shadow map and atlas-sized targets), freed after.
    uint64_t peakBytes = 0;
};

// Leaves the GL state as the frame expects it (default framebuffer, the scene's vertex array,
// depth test and writes on, blending off) and the GL finished, so that a wall clock around it
// measures the whole bake.
BakedLightmap bakeLightmap(const Light& light, const GpuScene& scene, const LightmapAtlas& atlas,
                           const BakeSettings& settings);

}  // namespace so
