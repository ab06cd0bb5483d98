// slope-bias (slope_bias.cpp): the depth test with the slope-scaled bias.
float techniqueVisibility(Receiver r) {
    return depthTest(r.p, slopeBias(r, SLOPE_ALPHA, SLOPE_MIN, SLOPE_MAX, 1.0));
}
