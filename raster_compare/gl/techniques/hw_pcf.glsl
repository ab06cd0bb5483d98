// hw-pcf (hw_pcf.cpp): the sampler's compare at the slope-biased depth.
float techniqueVisibility(Receiver r) {
    return hardwareTest(r.p, slopeBias(r, SLOPE_ALPHA, SLOPE_MIN, SLOPE_MAX, 1.0));
}
