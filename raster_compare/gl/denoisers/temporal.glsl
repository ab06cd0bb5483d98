// temporal (temporal.cpp): the reprojected exponential history of V and its first two moments,
// with the history length (reprojection.glsl's reprojected()); svgf and penumbra run it first.
uniform sampler2D u_raw;
uniform float u_newWeight;  // 1 - history: the new frame's weight
uniform float u_maxLength;  // the history length's cap: svgf 32 as Falcor (SVGFReproject 216)
layout(location = 0) out vec4 o_accum;

void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    vec4 pos = positionAt(ij);
    if (pos.w == 0.0) {
        o_accum = vec4(0.0);
        return;
    }
    SO_TAP(1, RAW_TEXEL_BYTES);
    float v = texelFetch(u_raw, ij, 0).r;
    vec4 hist = u_haveHistory != 0 ? reprojected(pos.xyz, normalAt(ij)) : vec4(0.0);
    if (hist.w < 0.5) {
        o_accum = vec4(v, v, v * v, 1.0);
        return;
    }
    // SVGF 4.1: an exponential moving average, the first frames of a history averaged equally.
    float len = min(round(hist.w) + 1.0, u_maxLength);
    float a = max(u_newWeight, 1.0 / len);
    o_accum = vec4(mix(hist.x, v, a), mix(hist.y, v, a), mix(hist.z, v * v, a), len);
}
