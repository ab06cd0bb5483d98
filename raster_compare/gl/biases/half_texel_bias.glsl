// bias=half-texel (half_texel_bias.cpp): the tangent plane's depth at the tap, less the rise it needs
// over half a texel along each map axis and the depth buffer's rounding.
struct BiasState {
    vec2 g;  // the tangent plane's depth change per texel of offset
};
BiasState biasState(Receiver r, MapPoint m) { return BiasState(tangentPlaneGradient(r, m)); }
vec3 biasedPoint(Receiver r) { return r.p; }
float biasedDepth(BiasState b, Receiver r, MapPoint m, vec2 o, float planeDepth) {
    return m.d + dot(b.g, o) - 0.5 * (abs(b.g.x) + abs(b.g.y)) - depthPrecision(m.d, b.g);
}
