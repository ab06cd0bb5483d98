// bias=texel-plane (texel_plane_bias.cpp): the receiver's depth at each tap's texel centre, on the
// plane its screen-space derivatives span, less the depth buffer's rounding.
struct BiasState {
    vec2 g;  // the plane's depth change per texel of offset
};
BiasState biasState(Receiver r, MapPoint m) { return BiasState(screenPlaneGradient(r, m)); }
vec3 biasedPoint(Receiver r) { return r.p; }
float biasedDepth(BiasState b, Receiver r, MapPoint m, vec2 o, float planeDepth) {
    return m.d + dot(b.g, tapTexelCentre(m, o)) - depthPrecision(m.d, b.g);
}
