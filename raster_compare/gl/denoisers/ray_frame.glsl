// The ray-traced family's passes (denoisers/ray_frame.h): what every pass reads. Every texture is
// in GL's row order; every fetch is a tap of the work counts (SO_TAP), with the texel bytes
// defined by RayFrame::program (RAW_, ACCUM_, FILTER_, TILE_, RESULT_, POSITION_ and
// NORMAL_TEXEL_BYTES); one pass's define (PASS_TEMPORAL, ...) picks the pass in a file with more.
uniform sampler2D u_position;
uniform sampler2D u_normal;
uniform vec3 u_lsEye;
uniform float u_pixelScale;

vec4 positionAt(ivec2 q) {
    SO_TAP(1, POSITION_TEXEL_BYTES);
    return texelFetch(u_position, q, 0);
}
vec3 normalAt(ivec2 q) {
    SO_TAP(1, NORMAL_TEXEL_BYTES);
    return normalize(texelFetch(u_normal, q, 0).xyz);
}
// One pixel's footprint at the local point lsP: how far apart neighbouring pixels' surfaces lie
// there (the tangent-plane stops' unit).
float footprintAt(vec3 lsP) {
    return u_pixelScale * length(lsP - u_lsEye);
}
// Per mesh, this frame's local point to where it stood in the frame before, in that frame's local
// frame: the camera's frames and the mesh's exact motion (RayFrame::bindHistory, from the caller's
// temporal state; without motion, the local frames' scale and offset alone).
layout(std430, binding = 0) readonly buffer PrevLocalFromLocal {
    mat4 u_prevLocalFromLocal[];
};
mat4 previousFromLocal() {
    SO_TAP(1, NORMAL_TEXEL_BYTES);
    return u_prevLocalFromLocal[int(texelFetch(u_normal, ivec2(gl_FragCoord.xy), 0).w)];
}
// This pixel's point lsP where it stood in the frame before.
vec3 previousLocal(vec3 lsP) {
    return (previousFromLocal() * vec4(lsP, 1.0)).xyz;
}
bool inside(ivec2 q, ivec2 size) {
    return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size));
}
