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
bool inside(ivec2 q, ivec2 size) {
    return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size));
}
