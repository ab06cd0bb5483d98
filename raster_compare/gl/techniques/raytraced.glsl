// raytraced (raytraced.cpp): the denoised V (the denoiser's result target) into the light's
// target. denoisers/ray_frame.glsl comes first; the denoisers' passes are their own files
// (denoisers/*.glsl).
uniform sampler2D u_result;  // R: V
layout(location = 0) out float o_visibility;
layout(location = 1) out float o_aliasing;
void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    SO_TAP(1, RESULT_TEXEL_BYTES);
    o_visibility = clamp(texelFetch(u_result, ij, 0).r, 0.0, 1.0);
    o_aliasing = 0.0;
}
