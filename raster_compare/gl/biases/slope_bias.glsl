// bias=slope (slope_bias.cpp): the slope-scaled bias, spread over the filter's reach.
struct BiasState {
    float unused;
};
BiasState biasState(Receiver r, MapPoint m) { return BiasState(0.0); }
vec3 biasedPoint(Receiver r) { return r.p; }
float biasedDepth(BiasState b, Receiver r, MapPoint m, vec2 o, float planeDepth) {
    return planeDepth - slopeBias(r, SLOPE_FACTOR, SLOPE_MIN, SLOPE_MAX, BIAS_SPREAD);
}
