// bias=adaptive (adaptive_bias.cpp): the tangent plane's depth at the tap's texel centre (the
// light's ray through it meets the plane there), less the depth buffer's precision at that depth.
struct BiasState {
    vec2 g;  // the tangent plane's depth change per texel of offset
};
BiasState biasState(Receiver r, MapPoint m) { return BiasState(tangentPlaneGradient(r, m)); }
vec3 biasedPoint(Receiver r) { return r.p; }
float biasedDepth(BiasState b, Receiver r, MapPoint m, vec2 o, float planeDepth) {
    float dCentre = m.d + dot(b.g, tapTexelCentre(m, o));
    return dCentre - depthPrecision(dCentre, b.g);
}
