// smrt's rays (smrt.cpp), whatever map they are marched through: SMRT_RAYS rays from the receiver
// toward points on the light, each sampled SMRT_SAMPLES times as a height field; V the share with
// no blocked sample. The frame that includes it defines, after it, where a sample falls:
// heightSample (the plain map: techniques/smrt.glsl; the virtual map's pages:
// shaders/smrt_virtual.frag) and mapDepth; and before it u_lsLightPosition, u_lsLightDirection,
// u_lsEye and shaders/taps.glsl.
uniform int u_smrtShape;  // 0 none, 1 rectangle, 2 disk (u, v), 3 disk of u_smrtWidth facing p
uniform vec3 u_lsLightU;
uniform vec3 u_lsLightV;
uniform float u_smrtWidth;
// How far deeper than the ray the surface at its crossing point may lie and still be the surface it
// crossed, in the step's climb: a sloped occluder's surface there is not at the sample's depth,
// which rayBlocked extrapolates flat; the ground beside an occluder's edge lies far deeper. (0 and
// 0.5 gave the same penumbra on the rect light's closed-form scene.)
#define SMRT_CROSS_TOLERANCE 0.5

// What the map holds where a sample falls: `covered` false where nothing was rendered that could
// shadow it (beyond the map); else the sample's linear depth along the map's axis, the depth
// stored there and the world size of the texel that was read.
struct HeightSample {
    bool covered;
    float d;
    float stored;
    float texel;
};
HeightSample heightSample(vec3 q);
float mapDepth(vec3 q);  // a point's linear depth along the map's axis

// Point k of the light's shape for a ray, `turn` in [0, 1) turning the set per pixel and frame.
vec3 lightPoint(vec3 p, int k, float turn) {
    vec3 centre = u_lsLightPosition;
    if (u_smrtShape == 1) {
        // A Fibonacci lattice over the square (k / n along u, the golden ratio's multiples along
        // v: n distinct, even steps on either edge's axis), shifted round the torus by the turn.
        vec2 s = fract(vec2((float(k) + 0.5) / float(SMRT_RAYS), (float(k) + 0.5) * 0.618034) +
                       vec2(turn, 0.618034 * turn)) - 0.5;
        return centre + s.x * u_lsLightU + s.y * u_lsLightV;
    }
    vec2 d = vogelTap(k, SMRT_RAYS, 6.28318531 * turn);
    if (u_smrtShape == 2) return centre + 0.5 * (d.x * u_lsLightU + d.y * u_lsLightV);
    if (u_smrtShape == 3) {
        vec3 w = normalize(p - centre);
        vec3 a = normalize(cross(w, abs(w.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0)));
        return centre + 0.5 * u_smrtWidth * (d.x * a + d.y * cross(w, a));
    }
    return centre;
}

// Whether the segment from p to `target` crosses the height field: a sample behind the stored
// depth by less than the ray climbs to the next sample (the ray may have passed through the
// occluder's surface in that step; further behind, it ran under the occluder's shadow from the
// centre and came out beside it), and where the ray reaches that surface's depth the map holds it
// there (the crossing; Unreal's "occluder slope extrapolated behind it", flat here). The crossing
// took the rect light's penumbra over a parallel square from 1.46-1.51 times pcss's mae to
// 1.07-1.13 (96 x 72 to 320 x 240) and lowered it on 7 of 9 other area lights; a thick occluder
// that a near-horizontal ray enters through one side and leaves through another it misses
// (soft_chair's window: 0.078 -> 0.088; alpha_grate's panel too: 0.094 -> 0.115, docs/techniques.md).
// The slope bias is `bias` (a length) at the receiver, whose texel is `texel`, and scales with the
// texel each sample reads.
bool rayBlocked(vec3 p, vec3 target, float h, float bias, float texel) {
    vec3 w = target - p;
    for (int j = 0; j < SMRT_SAMPLES; ++j) {
        float t = (float(j) + h) / float(SMRT_SAMPLES);
        float tNext = min((float(j + 1) + h) / float(SMRT_SAMPLES), 1.0);
        HeightSample s = heightSample(p + w * (t * t));
        if (!s.covered) continue;
        float climb = abs(s.d - mapDepth(p + w * (tNext * tNext)));
        float behind = s.d - bias * (s.texel / texel) - s.stored;
        if (!(behind > 0.0 && behind < climb + s.texel)) continue;
        // The ray crosses the surface the sample sees within this step: where, taking that surface
        // on at the sample's depth (its slope extrapolated flat), and is it there? A sample just
        // inside an occluder's edge whose ray crosses the occluder's plane just outside sees the
        // ground there: the ray passes beside the edge.
        float u = mix(t * t, tNext * tNext, clamp(behind / max(climb, 1e-12), 0.0, 1.0));
        HeightSample x = heightSample(p + w * u);
        if (!x.covered) return true;
        if (x.d - bias * (x.texel / texel) - x.stored > -(x.texel + SMRT_CROSS_TOLERANCE * climb))
            return true;
    }
    return false;
}

// V at the receiver p (covered by the map), its slope bias `bias` for its own texel `texel`.
float smrtVisibility(vec3 p, float bias, float texel) {
    // One set of light points for every pixel (a smooth, stepped penumbra, as pcss's spiral); with
    // TEMPORAL turned per pixel and frame, the history resolving the noise.
#ifdef TEMPORAL
    float turn = tapRotation() / 6.28318531;
#else
    float turn = 0.0;
#endif
    int lit = 0;
    for (int k = 0; k < SMRT_RAYS; ++k) {
#ifdef LIGHT_ORTHO
        vec3 target = p - u_lsLightDirection * (SMRT_LENGTH_SCALE * distance(p, u_lsEye));
#else
        vec3 target = lightPoint(p, k, turn);
#endif
        // Each ray its own fraction of a step (a golden-ratio walk from the pixel's turn).
        float h = fract(turn + 0.618034 * float(k)) * 0.999 + 0.0005;
        if (!rayBlocked(p, target, h, bias, texel)) ++lit;
    }
    return float(lit) / float(SMRT_RAYS);
}
