// bias=receiver-plane (receiver_plane_bias.cpp): each tap at the receiver's depth plus the plane's
// rise to the tap (Isidoro 2006), less the fractional sampling error, capped (TheRealMJP/Shadows
// Mesh.hlsl:130-132 and :190-193).
struct BiasState {
    vec2 g;        // the plane's depth change per texel of offset (receiverPlaneDepthBias)
    float margin;  // min(fractionalSamplingError, cap) + the depth precision, a length
};
BiasState biasState(Receiver r, MapPoint m) {
    vec2 g = screenPlaneGradient(r, m);
    // dot(texelSize, abs(receiverPlaneDepthBias)): the plane's rise over a texel along each axis.
    float fractionalSamplingError = MARGIN_TEXELS * (abs(g.x) + abs(g.y));
    float margin = min(fractionalSamplingError, windowDepthLength(m.d, MARGIN_CAP));
    // Plus the depth buffer's rounding, which a perspective map's window depth needs (MJP's
    // orthographic cascades have none to speak of).
    return BiasState(g, margin + depthPrecision(m.d, g));
}
vec3 biasedPoint(Receiver r) { return r.p; }
float biasedDepth(BiasState b, Receiver r, MapPoint m, vec2 o, float planeDepth) {
    return m.d + dot(b.g, o) - b.margin;
}
