// smrt's rays (smrt.cpp), whatever map they are marched through: SMRT_RAYS rays from the receiver
// toward points on the light, each traced from its light end toward the receiver through
// SMRT_SAMPLES + 1 samples of the map (EEVEE-Next's shadow_map_trace, whose hit check this is);
// V the share of rays that hit nothing. The frame that includes it defines, after it, where a
// sample falls: heightSample (the plain map: techniques/smrt.glsl; the virtual map's pages:
// shaders/smrt_virtual.frag) and mapDepth; and before it u_lsLightPosition, u_lsLightDirection,
// u_lsEye and shaders/taps.glsl.
uniform int u_smrtShape;  // 0 none, 1 rectangle, 2 disk (u, v), 3 disk of u_smrtWidth facing p
uniform vec3 u_lsLightU;
uniform vec3 u_lsLightV;
uniform float u_smrtWidth;
// tan(max_ray_angle) for a local light (a negative value: no limit, as for a sun), and the bound
// on the occluder's depth slope extrapolated behind it (extrapolate_slope, the light's type's
// default resolved on the CPU).
uniform float u_smrtTanMaxRayAngle;
uniform float u_smrtMaxSlope;

// What the map holds where a sample falls: `covered` false where nothing was rendered that could
// shadow it (beyond the map, a page not resident); else the sample's linear depth along the map's
// axis, the depth stored there and the world size of the texel that was read.
struct HeightSample {
    bool covered;
    float d;
    float stored;
    float texel;
};
HeightSample heightSample(vec3 q);
float mapDepth(vec3 q);  // a point's linear depth along the map's axis

// The pixel's two random numbers in [0, 1): interleaved gradient noise (shaders/taps.glsl) at the
// pixel and at a far-off pixel, each pixel its own light points and step offset (Unreal's
// per-pixel random sample points); with TEMPORAL (temporal=on) they also move per frame.
vec2 pixelRandom() {
    const float inverseTwoPi = 0.15915494;
    float a = tapRotation() * inverseTwoPi;
    float b = fract(a + interleavedGradientNoise(gl_FragCoord.xy + vec2(113.0, 71.0)));
    return vec2(a, b);
}

// Point k of the light's shape for a ray, the set shifted by the pixel's random pair.
vec3 lightPoint(vec3 p, int k, vec2 random) {
    vec3 centre = u_lsLightPosition;
    if (u_smrtShape == 1) {
        // A Fibonacci lattice over the square (k / n along u, the golden ratio's multiples along
        // v: n distinct, even steps on either axis), shifted round the torus (Cranley-Patterson).
        vec2 s = fract(vec2((float(k) + 0.5) / float(SMRT_RAYS), (float(k) + 0.5) * 0.618034) +
                       random) - 0.5;
        return centre + s.x * u_lsLightU + s.y * u_lsLightV;
    }
    vec2 d = vogelTap(k, SMRT_RAYS, 6.28318531 * random.x);
    if (u_smrtShape == 2) return centre + 0.5 * (d.x * u_lsLightU + d.y * u_lsLightV);
    if (u_smrtShape == 3) {
        vec3 w = normalize(p - centre);
        vec3 a = normalize(cross(w, abs(w.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0)));
        return centre + 0.5 * u_smrtWidth * (d.x * a + d.y * cross(w, a));
    }
    return centre;
}

// The fraction of the segment p -> q that a local light's ray keeps: seen from the light's centre
// c, the ray from p may span at most max_ray_angle (Unreal's MaxRayAngleFromLight). With a = p - c
// and d = q - p split along and across a, the angle at s is atan(s |d_across| / (|a| + s d_along)).
float rayFractionWithinAngle(vec3 p, vec3 q) {
    if (u_smrtTanMaxRayAngle < 0.0) return 1.0;
    vec3 a = p - u_lsLightPosition, d = q - p;
    float lengthA = length(a);
    float along = dot(d, a) / max(lengthA, 1e-12);
    float across = length(d - along * a / max(lengthA, 1e-12));
    float denominator = across - u_smrtTanMaxRayAngle * along;
    if (denominator <= 0.0) return 1.0;
    return clamp(u_smrtTanMaxRayAngle * lengthA / denominator, 0.0, 1.0);
}

// EEVEE-Next's hit check (eevee_shadow_tracing_lib.glsl, shadow_map_trace_hit_check): the ray is
// traced from its light end toward the receiver p, the samples crowding toward p (the fraction
// ((n - i - h) / n)^2 of the way, i = 0..n, the last at p itself). The first covered sample is a
// plain depth test. After it, a sample whose ray lies behind the map's occluder by more than the
// ray's own step (1.05 times it) is behind that occluder, not crossing it: it is tested against
// the last occluder seen in front of the ray, extrapolated along that occluder's depth slope
// (clamped to +-u_smrtMaxSlope, in occluder depth per unit of the ray's depth); otherwise it is
// tested against the map and the slope is updated. Depths are the map's linear depths, the ray's
// less the slope bias (`bias` at the receiver whose texel is `texel`, scaled with each sample's).
bool rayBlocked(vec3 p, vec3 end, float h, float bias, float texel) {
    vec3 w = end - p;
    bool started = false;
    float rayBefore = 0.0;      // the ray's depth at the last sample it was not blocked at
    float occluderBefore = 0.0; // the last occluder depth seen in front of the ray
    float timeBefore = 0.0;     // the ray's unbiased depth there (EEVEE's ray time, in depth)
    float slope = 0.0;
    for (int i = 0; i <= SMRT_SAMPLES; ++i) {
        float t = clamp(1.0 - (float(i) + h) / float(SMRT_SAMPLES), 0.0, 1.0);
        HeightSample s = heightSample(p + w * (t * t));
        if (!s.covered) continue;  // EEVEE: skip_sample (the slope history stays)
        float ray = s.d - bias * (s.texel / texel);
        float occluder = s.stored;
        if (!started) {
            if (occluder < ray) return true;
            started = true;
            rayBefore = ray, occluderBefore = occluder, timeBefore = s.d;
            continue;
        }
        if (occluder < ray - 1.05 * abs(ray - rayBefore)) {
            occluder = occluderBefore + slope * (s.d - timeBefore);
        } else {
            float step = s.d - timeBefore;
            slope = abs(step) > 1e-12 ? (occluder - occluderBefore) / step : 0.0;
            slope = clamp(slope, -u_smrtMaxSlope, u_smrtMaxSlope);
            occluderBefore = occluder, timeBefore = s.d;
        }
        if (occluder < ray) return true;
        rayBefore = ray;
    }
    return false;
}

// V at the receiver p (covered by the map), its slope bias `bias` for its own texel `texel`.
float smrtVisibility(vec3 p, float bias, float texel) {
    vec2 random = pixelRandom();
    int lit = 0;
    for (int k = 0; k < SMRT_RAYS; ++k) {
#ifdef LIGHT_ORTHO
        // A sun: rays ray_length_scale times the receiver's distance to the camera long; Unreal
        // bounds no angle for directional lights (MaxRayAngleFromLight is for local lights).
        vec3 end = p - u_lsLightDirection * (SMRT_LENGTH_SCALE * distance(p, u_lsEye));
#else
        vec3 q = lightPoint(p, k, random);
        vec3 end = p + (q - p) * rayFractionWithinAngle(p, q);
#endif
        // Each ray its own step offset (a golden-ratio walk from the pixel's second number).
        float h = fract(random.y + 0.618034 * float(k)) * 0.999 + 0.0005;
        if (!rayBlocked(p, end, h, bias, texel)) ++lit;
    }
    return float(lit) / float(SMRT_RAYS);
}
