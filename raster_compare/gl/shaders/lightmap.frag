// The lightmap family's visibility frame (lightmap.h): V of one light per pixel, looked up in the
// baked atlas. The technique's GLSL file (techniques/lightmap.glsl) follows and defines
// lightmapLookup, the filter. Where the light does not face the surface, or a spot's cone does not
// hold it, V = 0 as in the oracle; a mesh that was not baked (dynamic) has no texels: lit wherever
// the light faces it. Otherwise the point's atlas coordinates come from its triangle's affine map
// (two rows per triangle, exact at the corners the bake rasterised), found by the mesh's first
// triangle and gl_PrimitiveID. Defines: LIGHT_ORTHO (directional), LIGHT_SPOT.
in vec3 v_lsPosition;
flat in vec3 v_lsFaceNormal;
uniform vec3 u_lsEye;
uniform vec3 u_lsLightPosition;
uniform vec3 u_lsLightDirection;  // the way light travels
uniform float u_cosOuter;
uniform float u_pixelScale;  // camera pixel size per unit of distance
uniform float u_meshId;
uniform float u_lsTexel;  // the world size of one texel, local units (1 / texels_per_unit)
layout(binding = 0) uniform sampler2D u_atlas;
layout(std430, binding = 0) readonly buffer TexelFromLocal {
    vec4 texelFromLocal[];  // per triangle: rows 2t and 2t + 1
};
layout(std430, binding = 1) readonly buffer MeshFirstTriangle {
    int meshFirstTriangle[];  // per mesh: its first triangle's row pair, -1 if not baked
};
layout(location = 0) out float o_visibility;
// Predicted aliasing: a texel's footprint on the surface over the camera pixel's there.
layout(location = 1) out float o_aliasing;

float lightmapLookup(vec2 texel);  // the technique's: V at atlas coordinates in texels

void main() {
    alphaTest();
    vec3 p = v_lsPosition;
    vec3 n = normalize(v_lsFaceNormal);
    if (dot(n, p - u_lsEye) > 0.0) n = -n;
#ifdef LIGHT_ORTHO
    vec3 l = -u_lsLightDirection;
#else
    vec3 l = normalize(u_lsLightPosition - p);
#endif
    o_aliasing = 0.0;
    o_visibility = 0.0;
    if (dot(n, l) <= 0.0) return;
#ifdef LIGHT_SPOT
    if (dot(-l, u_lsLightDirection) < u_cosOuter) return;
#endif
    int first = meshFirstTriangle[int(u_meshId)];
    if (first < 0) {
        o_visibility = 1.0;
        return;
    }
    int t = first + gl_PrimitiveID;
    vec4 q = vec4(p, 1.0);
    vec2 texel = vec2(dot(texelFromLocal[2 * t], q), dot(texelFromLocal[2 * t + 1], q));
    vec3 toEye = u_lsEye - p;
    float pixel = length(toEye) * u_pixelScale / max(abs(dot(n, normalize(toEye))), 1e-3);
    o_aliasing = u_lsTexel / pixel;
    o_visibility = lightmapLookup(texel);
}
