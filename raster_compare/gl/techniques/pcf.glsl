// pcf (pcf.cpp): the depth test averaged over a grid of (2 PCF_RADIUS + 1)^2 texels, or over a
// 16-tap Poisson disk (POISSON), each tap at the depth its bias gives (BIAS_SPREAD: the slope
// bias spread over the kernel); with TEMPORAL, as many
// taps (PCF_TAPS) on a Vogel disk of PCF_DISK_TEXELS texels turned per pixel and frame;
// PATTERN_ENGINE (PATTERN_THREE, PATTERN_BEVY, PATTERN_GODOT): an engine's PCF_TAPS taps, each the
// sampler's 2x2 compare (MAP_HW_COMPARE), turned as that engine turns them (pcf.cpp cites where).
#ifdef PATTERN_ENGINE
// The sampler's compare at an offset o in texels from the point (cube maps: on m's face axes).
float hardwareTapAt(MapPoint m, vec2 o, float dRef) {
    SO_TAP(MAP_FILTER_TEXELS, MAP_TEXEL_BYTES);
#ifdef LIGHT_CUBE
    return texture(u_map, vec4(m.v + m.step * (o.x * m.t1 + o.y * m.t2), windowDepth(dRef)));
#elif defined(CASCADES)
    return texture(u_map, vec4(m.uv + o / vec2(MAP_SIZE), float(g_cascade), windowDepth(dRef)));
#else
    return texture(u_map, vec3(m.uv + o / vec2(MAP_SIZE), windowDepth(dRef)));
#endif
}
// Bevy's and Godot's rotation matrix, mat2(c, -s, s, c) (column-major): a turn by -angle.
vec2 turnedBack(vec2 v, float angle) {
    float c = cos(angle), s = sin(angle);
    return vec2(c * v.x + s * v.y, -s * v.x + c * v.y);
}
#ifdef PATTERN_BEVY
// utils.wesl SPIRAL_OFFSET_0_ .. 7_ (Jimenez 2014, slides 120-135).
const vec2 kBevySpiral[8] = vec2[](vec2(-0.7071, 0.7071), vec2(-0.0000, -0.8750), vec2(0.5303, 0.5303),
                                   vec2(-0.6250, -0.0000), vec2(0.3536, -0.3536), vec2(-0.0000, 0.3750),
                                   vec2(-0.1768, -0.1768), vec2(0.1250, 0.0000));
// calculate_uv_offset_scale_jimenez_fourteen in texels: map(0.00390625, 0.022949219, 0.015, 0.035,
// texel) / texel, texel the map's texel in world units (spots: SPOT_SHADOW_TEXEL_SIZE).
float bevyScaleTexels(float texel) {
    float f = 0.015 + (texel - 0.00390625) * (0.035 - 0.015) / (0.022949219 - 0.00390625);
    return f / texel;
}
float bevyTexels() {
#if defined(LIGHT_CUBE)
    return 0.003 * 0.5 / u_texelScale;  // POINT_SHADOW_SCALE x POINT_SHADOW_TEMPORAL_OFFSET_SCALE
#elif defined(LIGHT_SPOT)
    return bevyScaleTexels(0.0134277345);
#elif defined(CASCADES)
    return bevyScaleTexels(u_cascadeTexel[g_cascade]);
#else
    return bevyScaleTexels(u_texelScale);
#endif
}
#endif
// Tap k's offset in texels.
vec2 enginePatternTap(int k) {
#if defined(PATTERN_THREE)
    // phi = interleavedGradientNoise(gl_FragCoord.xy) * PI2: the pixel alone, no frame term.
    float phi = 6.28318531 * interleavedGradientNoise(gl_FragCoord.xy);
#ifdef LIGHT_CUBE
    return vogelTap(k, PCF_TAPS, phi) * (0.5 * PATTERN_TEXELS);  // radius / mapSize in directions
#else
    return vogelTap(k, PCF_TAPS, phi) * PATTERN_TEXELS;
#endif
#elif defined(PATTERN_BEVY)
    // interleaved_gradient_noise(frag, frame_count): the pixel moved by 5.588238 (frame % 64).
    float turn = 6.28318531 * interleavedGradientNoise(gl_FragCoord.xy + 5.588238 * float(u_frameIndex % 64));
    return turnedBack(kBevySpiral[k], turn) * bevyTexels();
#else
    // quick_hash(gl_FragCoord.xy + taa_frame_count * 5.588238); get_vogel_disk's golden angle 2.4.
    // taa_frame_count = frame_number % jitter_phase_count: % 16 with TAA (Godot 4.6
    // renderer_scene_cull.cpp, the TAA's 16 jitter phases).
    // Without TAA (or FSR2) taa_frame_count is 0: the pattern turns per pixel only.
#ifdef GODOT_TAA
    float turn = 6.28318531 * interleavedGradientNoise(gl_FragCoord.xy + 5.588238 * float(u_frameIndex % 16));
#else
    float turn = 6.28318531 * interleavedGradientNoise(gl_FragCoord.xy);
#endif
    float a = float(k) * 2.4;
    vec2 disk = sqrt((float(k) + 0.5) / float(PCF_TAPS)) * vec2(cos(a), sin(a));
    return turnedBack(disk, turn) * PATTERN_TEXELS;
#endif
}
#endif
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
#if defined(PATTERN_ENGINE)
    for (int k = 0; k < PCF_TAPS; ++k) {
        vec2 o = enginePatternTap(k);
        lit += hardwareTapAt(m, o, biasedDepth(b, r, m, o, m.d));
    }
    return lit / float(PCF_TAPS);
#elif defined(TEMPORAL)
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
