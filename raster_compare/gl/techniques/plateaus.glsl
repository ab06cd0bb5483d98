// plateaus (plateaus.cpp): the cones and edge quads, flattened onto the receiver's plane, carry
// the attenuation (0 at the hard shadow's edge, 1 at the plateau's rim) that the MIN blend keeps
// the least of per pixel, as Haines's depth test did.
#ifdef SO_VERTEX_SHADER
layout(location = 0) in vec4 a_lsPlateau;  // xyz: on the lifted plane; w: the attenuation
uniform mat4 u_clipFromLocal;
out float v_attenuation;
void main() {
    v_attenuation = a_lsPlateau.w;
    gl_Position = u_clipFromLocal * vec4(a_lsPlateau.xyz, 1.0);
}
#else
in float v_attenuation;
layout(location = 0) out vec4 o_visibility;
void main() { o_visibility = vec4(v_attenuation, 0.0, 0.0, 1.0); }
#endif
