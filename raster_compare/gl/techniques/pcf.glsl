// pcf (pcf.cpp): the depth test averaged over a grid of (2 PCF_RADIUS + 1)^2 texels, or over a
// 16-tap Poisson disk (POISSON), each tap at the depth its bias gives (BIAS_SPREAD: the slope
// bias spread over the kernel); with TEMPORAL, as many
// taps (PCF_TAPS) on a Vogel disk of PCF_DISK_TEXELS texels turned per pixel and frame.
#ifdef POISSON
// 16 points of a Poisson disk in the unit disk.
const vec2 kPoisson[16] = vec2[](vec2(-0.94201624, -0.39906216), vec2(0.94558609, -0.76890725), vec2(-0.09418410, -0.92938870),
                                 vec2(0.34495938, 0.29387760), vec2(-0.91588581, 0.45771432), vec2(-0.81544232, -0.87912464),
                                 vec2(-0.38277543, 0.27676845), vec2(0.97484398, 0.75648379), vec2(0.44323325, -0.97511554),
                                 vec2(0.53742981, -0.47373420), vec2(-0.26496911, -0.41893023), vec2(0.79197514, 0.19090188),
                                 vec2(-0.24188840, 0.99706507), vec2(-0.81409955, 0.91437590), vec2(0.19984126, 0.78641367),
                                 vec2(0.14383161, -0.14100790));
#endif

float techniqueVisibility(Receiver r) {
    r.p = biasedPoint(r);
    MapPoint m = mapPoint(r.p);
    if (m.outside) return 1.0;
    BiasState b = biasState(r, m);
    float lit = 0.0;
#if defined(TEMPORAL)
    float turn = tapRotation();
    for (int k = 0; k < PCF_TAPS; ++k) {
        vec2 o = vogelTap(k, PCF_TAPS, turn) * PCF_DISK_TEXELS;
        lit += depthTapAt(m, o, biasedDepth(b, r, m, o, m.d));
    }
    return lit / float(PCF_TAPS);
#elif defined(POISSON)
    for (int k = 0; k < 16; ++k) {
        vec2 o = kPoisson[k] * (float(PCF_RADIUS) + 0.5);
        lit += depthTapAt(m, o, biasedDepth(b, r, m, o, m.d));
    }
    return lit / 16.0;
#else
    for (int dy = -PCF_RADIUS; dy <= PCF_RADIUS; ++dy)
        for (int dx = -PCF_RADIUS; dx <= PCF_RADIUS; ++dx)
            lit += depthTap(m, ivec2(dx, dy), biasedDepth(b, r, m, vec2(dx, dy), m.d));
    return lit / float((2 * PCF_RADIUS + 1) * (2 * PCF_RADIUS + 1));
#endif
}
