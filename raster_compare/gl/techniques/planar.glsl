// planar (planar.cpp): the vertex shader that flattens the casters onto the receiver's plane.
// u_projection is Blinn's (P.L) I - L P^T for the lifted plane P and the light L (homogeneous);
// clip distance 0 drops what projects with w <= 0 (casters beyond a point light), clip distance 1
// what lies below the receiver's plane (it would cast upwards through it). The caster's alpha-mask
// uv goes along (perspective-correct through the projection, as the flattened triangle is a
// projective image of the caster's), so blend_alpha.frag's alpha test cuts its holes.
layout(location = 0) in vec3 a_lsPosition;
layout(location = 2) in vec2 a_uv;
uniform mat4 u_clipFromLocal;
uniform mat4 u_projection;
uniform vec4 u_lsPlane;  // the plane projected onto, n towards the light
out vec2 v_uv;
void main() {
    v_uv = a_uv;
    vec4 q = u_projection * vec4(a_lsPosition, 1.0);
    gl_ClipDistance[0] = q.w;
    gl_ClipDistance[1] = dot(u_lsPlane, vec4(a_lsPosition, 1.0));
    gl_Position = u_clipFromLocal * q;
}
