// bias=normal-offset (normal_offset_bias.cpp): the lookup point moved along the normal, then a
// constant bias.
struct BiasState {
    float unused;
};
BiasState biasState(Receiver r, MapPoint m) { return BiasState(0.0); }
vec3 biasedPoint(Receiver r) { return r.p + r.n * (NORMAL_OFFSET_TEXELS * r.texel * (1.0 - r.ndotl)); }
float biasedDepth(BiasState b, Receiver r, MapPoint m, vec2 o, float planeDepth) {
    return planeDepth - NORMAL_DEPTH_TEXELS * r.texel;
}
