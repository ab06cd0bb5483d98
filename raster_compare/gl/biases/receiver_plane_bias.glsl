// bias=receiver-plane (receiver_plane_bias.cpp): the receiver's depth at each tap's texel centre,
// on the plane its screen-space derivatives span, less the depth buffer's rounding.
struct BiasState {
    vec2 g;  // the plane's depth change per texel of offset
};
BiasState biasState(Receiver r, MapPoint m) {
    // A pixel's step can span many texels: the same plane, a texel long, keeps the projection's
    // curvature (perspective maps) out of the differences.
    vec3 e1 = g_dpdx * (r.texel / max(length(g_dpdx), 1e-30));
    vec3 e2 = g_dpdy * (r.texel / max(length(g_dpdy), 1e-30));
    return BiasState(receiverPlaneGradient(m, r.p, e1, e2));
}
vec3 biasedPoint(Receiver r) { return r.p; }
float biasedDepth(BiasState b, Receiver r, MapPoint m, vec2 o, float planeDepth) {
    return m.d + dot(b.g, tapTexelCentre(m, o)) - depthPrecision(m.d, b.g);
}
