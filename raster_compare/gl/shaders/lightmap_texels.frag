// The lightmap's bake (lightmap_bake.h): each covered texel's surface point (w = 1; an uncovered
// texel keeps w = 0) and its face normal turned towards the light (an area light's centre), as
// accumulate.glsl's weight pass reads them. Defines: LIGHT_ORTHO (directional).
in vec3 v_lsPosition;
flat in vec3 v_lsFaceNormal;
uniform vec3 u_lsLightPosition;
uniform vec3 u_lsLightDirection;  // the way light travels
layout(location = 0) out vec4 o_position;
layout(location = 1) out vec4 o_normal;
void main() {
    vec3 n = normalize(v_lsFaceNormal);
#ifdef LIGHT_ORTHO
    vec3 l = -u_lsLightDirection;
#else
    vec3 l = u_lsLightPosition - v_lsPosition;
#endif
    if (dot(n, l) < 0.0) n = -n;
    o_position = vec4(v_lsPosition, 1.0);
    o_normal = vec4(n, 0.0);
}
