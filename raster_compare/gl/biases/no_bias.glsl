// bias=none (no_bias.cpp): the receiver at the depth the filter puts it.
struct BiasState {
    float unused;
};
BiasState biasState(Receiver r, MapPoint m) { return BiasState(0.0); }
vec3 biasedPoint(Receiver r) { return r.p; }
float biasedDepth(BiasState b, Receiver r, MapPoint m, vec2 o, float planeDepth) { return planeDepth; }
