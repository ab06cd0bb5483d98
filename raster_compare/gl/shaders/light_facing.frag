// Families without a map (light_facing.h): V = 1 where the light faces the surface, the surface is
// in front of a one-sided emitter (rect, disk) and a spot's cone holds it, 0 elsewhere, as in the
// oracle; no texels, so no predicted aliasing (0).
// Defines: LIGHT_ORTHO (directional), LIGHT_SPOT.
in vec3 v_lsPosition;
flat in vec3 v_lsFaceNormal;
uniform vec3 u_lsEye;
uniform vec3 u_lsLightPosition;
uniform vec3 u_lsLightDirection;  // the way light travels
uniform float u_cosOuter;
uniform vec3 u_lsEmitNormal;  // rect, disk: the side they emit on; zero: every side
layout(location = 0) out float o_visibility;
layout(location = 1) out float o_aliasing;  // no map, no texels: 0
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
    o_visibility = dot(n, l) > 0.0 ? 1.0 : 0.0;
    if (u_lsEmitNormal != vec3(0.0) && dot(u_lsEmitNormal, p - u_lsLightPosition) <= 0.0)
        o_visibility = 0.0;
#ifdef LIGHT_SPOT
    if (dot(-l, u_lsLightDirection) < u_cosOuter) o_visibility = 0.0;
#endif
}
