// bias=constant (constant_bias.cpp): CONSTANT_TEXELS texels nearer the light.
struct BiasState {
    float unused;
};
BiasState biasState(Receiver r, MapPoint m) { return BiasState(0.0); }
vec3 biasedPoint(Receiver r) { return r.p; }
float biasedDepth(BiasState b, Receiver r, MapPoint m, vec2 o, float planeDepth) {
    return planeDepth - CONSTANT_TEXELS * r.texel;
}
