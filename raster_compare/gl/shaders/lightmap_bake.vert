// The lightmap's bake (lightmap_bake.h): the static triangles rasterised in the atlas's space, a
// fragment wherever a texel's centre is covered, with the surface point and its face normal there
// as varyings under the names the scene's frames read (shadow_map.frag, lightmap_texels.frag).
// The atlas coordinates are affine on each triangle, and so is the position: w = 1 interpolates
// both exactly. Drawn as points (a triangle's centroid), each covers the texel that holds it.
layout(location = 0) in vec3 a_lsPosition;
layout(location = 1) in vec3 a_lsFaceNormal;
layout(location = 2) in vec2 a_texel;  // atlas coordinates in texels
uniform vec2 u_atlasSize;
uniform float u_depth;  // 0: the triangles; 0.5: the centroids, where no triangle wrote
out vec3 v_lsPosition;
flat out vec3 v_lsFaceNormal;
void main() {
    v_lsPosition = a_lsPosition;
    v_lsFaceNormal = a_lsFaceNormal;
    gl_Position = vec4(a_texel / u_atlasSize * 2.0 - 1.0, u_depth, 1.0);
}
