// The shadow-map family's visibility frame: V of one light per pixel, in [0, 1]. The technique's
// GLSL file (techniques/*.glsl) follows this one and defines techniqueVisibility. Defines:
//   light: LIGHT_ORTHO (directional), LIGHT_SPOT, LIGHT_CUBE (point and area lights, at the centre);
//   CASCADES n with LIGHT_ORTHO: n orthographic maps, the layers of a 2D array, each covering a
//   slice of the camera's view depth; the lookups below read the cascade g_cascade;
//   map: MAP_DEPTH (point-sampled depth), MAP_HW_COMPARE (the sampler's depth compare),
//        MAP_MOMENTS (filtered moments); VISIBILITY_PASS;
//   MAP_TEXEL_BYTES (a map texel's bytes) and MAP_FILTER_TEXELS (the texels a filtered lookup
//   reads: 4 bilinear, 1 point-sampled), for the work counts' SO_TAP (gl_program.h).
//   DEPTH_PROBE with MAP_DEPTH: location 2 says what the pixel's own comparison saw (below).
//   RECEIVER_PLANE (DEPTH_BITS, DEPTH_STEPS): the receiver plane's helpers below, for any map;
//   the depth bias's file (biases/*.glsl, bias=NAME: shadow_maps/depth_bias.h) follows this one,
//   before the technique's; BIAS_SPREAD, how far the filter's taps reach (texels);
//   SCREEN_DERIVATIVES: g_dpdx, g_dpdy;
//   CONTACT: screen-space contact shadows (contact_method's shaders/contact_*.glsl, after the
//   technique's file), V the map's times theirs (as Bevy multiplies them).
// Depths are compared as linear distances along the map's view axis, so biases are lengths:
// in texels, the world size of one shadow-map texel at the receiver.
in vec3 v_lsPosition;
flat in vec3 v_lsFaceNormal;
uniform vec3 u_lsEye;
uniform vec3 u_lsLightPosition;
uniform vec3 u_lsLightDirection;  // the way light travels
uniform float u_cosOuter;
uniform vec3 u_lsEmitNormal;  // rect, disk: the side they emit on; zero: every side
uniform mat4 u_lightClipFromLocal;
uniform mat4 u_lightViewFromLocal;
uniform float u_near;
uniform float u_far;
uniform float u_texelScale;  // ortho: texel size; perspective: texel size per unit of depth
#if defined(MAP_HW_COMPARE) && defined(LIGHT_CUBE)
uniform samplerCubeShadow u_map;
#elif defined(MAP_HW_COMPARE) && defined(CASCADES)
uniform sampler2DArrayShadow u_map;
#elif defined(MAP_HW_COMPARE)
uniform sampler2DShadow u_map;
#elif defined(LIGHT_CUBE)
uniform samplerCube u_map;
#elif defined(CASCADES)
uniform sampler2DArray u_map;
#else
uniform sampler2D u_map;
#endif
#ifdef CASCADES
uniform mat4 u_cascadeClipFromLocal[CASCADES];
uniform float u_cascadeTexel[CASCADES];      // local units
uniform float u_cascadeSplit[CASCADES + 1];  // view depths (local units) bounding each cascade
uniform float u_cascadeBlend;                // fraction of a cascade's range fading into the next
uniform vec3 u_lsCameraForward;
int g_cascade = 0;  // the cascade the lookups read (main sets it)
// A texel of the current cascade, and the map's side.
#define MAP_TEXEL(ij) texelFetch(u_map, ivec3(ij, g_cascade), 0)
#define MAP_SIZE textureSize(u_map, 0).xy
#else
#define MAP_TEXEL(ij) texelFetch(u_map, ij, 0)
#define MAP_SIZE textureSize(u_map, 0)
#endif
uniform float u_pixelScale;  // camera pixel size per unit of distance (2 tan(vfov / 2) / height)
layout(location = 0) out float o_visibility;
// Predicted aliasing (Lloyd et al.): the shadow-map texel's footprint on the receiver over the
// camera pixel's footprint there; > 1 means a texel covers more than a pixel.
layout(location = 1) out float o_aliasing;

// What a technique gets: the receiver point, its camera-facing geometric normal, n.l (> 0) and
// the world size of one map texel there.
struct Receiver {
    vec3 p;
    vec3 n;
    float ndotl;
    float texel;
};
float techniqueVisibility(Receiver r);  // the technique's file
#ifdef CONTACT
// 0 where the march toward the light (l, at most maxLength) meets a surface the camera saw.
float contactVisibility(vec3 p, vec3 l, float maxLength);  // shaders/contact_<method>.glsl
#endif

// Turning taps (tapRotation, vogelTap, u_frameIndex): shaders/taps.glsl, before this file.

#ifdef DEPTH_PROBE
// What the pixel's own depth comparison saw (docs/exr-channels.md), so that compare can class a
// false shadow by its cause (docs/metrics.md): the linear depth the map holds at the receiver's
// own texel (the centre tap, whatever kernel the technique filters over; +inf beyond the map),
// the receiver's own linear depth (before any bias or offset), and one map texel's size there,
// all in local units; -1, -1, 0 where nothing is compared; and the map's own V (before contact
// shadows, which a screen-space pass adds: compare classes their false shadows as screen-space
// bleed, not acne), 0 where nothing is compared. A diagnostic: the counting build has
// no probe, so its lookup is no tap of the technique's work.
layout(location = 2) out vec4 o_depthProbe;
#endif

float linearDepth(float z) {
#ifdef LIGHT_ORTHO
    return u_near + z * (u_far - u_near);
#else
    return u_near * u_far / (u_far - z * (u_far - u_near));
#endif
}

float texelWorld(float depth) {
#ifdef CASCADES
    return u_cascadeTexel[g_cascade];
#elif defined(LIGHT_ORTHO)
    return u_texelScale;
#else
    return depth * u_texelScale;
#endif
}

// The window depth the hardware compares against, for a linear depth d.
float windowDepth(float d) {
#ifdef LIGHT_ORTHO
    return (d - u_near) / (u_far - u_near);
#else
    return u_far * (d - u_near) / (d * (u_far - u_near));
#endif
}

// Linear depth in [0, 1] between the map's near and far planes, as the moment maps store it.
float normalisedDepth(float d) { return clamp((d - u_near) / (u_far - u_near), 0.0, 1.0); }

// Where a point falls in the map: its linear depth d along the view axis; cube maps: the
// direction v from the light and the tangent axes of its face, `step` (one texel at depth d)
// apart; 2D maps: uv. `outside`: beyond the map, where nothing was rendered that could shadow it.
struct MapPoint {
    bool outside;
    float d;
    vec3 v, t1, t2;
    float step;
    vec2 uv;
};

MapPoint mapPoint(vec3 q) {
    MapPoint m;
#ifdef LIGHT_CUBE
    m.v = q - u_lsLightPosition;
    vec3 a = abs(m.v);
    m.d = max(a.x, max(a.y, a.z));
    m.outside = m.d > u_far;
    m.t1 = a.x >= a.y && a.x >= a.z ? vec3(0, 1, 0) : vec3(1, 0, 0);
    m.t2 = a.z >= a.x && a.z >= a.y ? vec3(0, 1, 0) : vec3(0, 0, 1);
    m.step = u_texelScale * m.d;
#else
#ifdef CASCADES
    vec4 c = u_cascadeClipFromLocal[g_cascade] * vec4(q, 1.0);
#else
    vec4 c = u_lightClipFromLocal * vec4(q, 1.0);
#endif
    m.uv = c.xy / c.w * 0.5 + 0.5;
    m.d = -(u_lightViewFromLocal * vec4(q, 1.0)).z;
    m.outside = any(lessThan(m.uv, vec2(0.0))) || any(greaterThan(m.uv, vec2(1.0))) || m.d > u_far;
#endif
    return m;
}

float receiverDepth(vec3 q) {
#ifdef LIGHT_CUBE
    vec3 a = abs(q - u_lsLightPosition);
    return max(a.x, max(a.y, a.z));
#else
    return -(u_lightViewFromLocal * vec4(q, 1.0)).z;
#endif
}

#if defined(MAP_DEPTH)
// 1 where a receiver at linear depth dRef is lit by the map's texel k texels (an integer offset)
// from the point's own, 0 where that texel holds something nearer.
float depthTap(MapPoint m, ivec2 k, float dRef) {
    SO_TAP(1, MAP_TEXEL_BYTES);
#ifdef LIGHT_CUBE
    float z = texture(u_map, m.v + m.step * (float(k.x) * m.t1 + float(k.y) * m.t2)).r;
#else
    ivec2 size = MAP_SIZE;
    ivec2 ij = clamp(ivec2(floor(m.uv * vec2(size))) + k, ivec2(0), size - 1);
    float z = MAP_TEXEL(ij).r;
#endif
    return dRef <= linearDepth(z) ? 1.0 : 0.0;
}
// The linear depth stored at an offset o in texels (need not be whole) from the point's texel.
float storedDepthAt(MapPoint m, vec2 o) {
    SO_TAP(1, MAP_TEXEL_BYTES);
#ifdef LIGHT_CUBE
    float z = texture(u_map, m.v + m.step * (o.x * m.t1 + o.y * m.t2)).r;
#else
    ivec2 size = MAP_SIZE;
    ivec2 ij = clamp(ivec2(floor(m.uv * vec2(size) + o)), ivec2(0), size - 1);
    float z = MAP_TEXEL(ij).r;
#endif
    return linearDepth(z);
}
// The depth test there.
float depthTapAt(MapPoint m, vec2 o, float dRef) { return dRef <= storedDepthAt(m, o) ? 1.0 : 0.0; }
#elif defined(MAP_HW_COMPARE)
// The sampler's own comparison (and its implementation-defined filter) at linear depth dRef.
float hardwareTap(MapPoint m, float dRef) {
    SO_TAP(MAP_FILTER_TEXELS, MAP_TEXEL_BYTES);
#ifdef LIGHT_CUBE
    return texture(u_map, vec4(m.v, windowDepth(dRef)));
#elif defined(CASCADES)
    return texture(u_map, vec4(m.uv, float(g_cascade), windowDepth(dRef)));
#else
    return texture(u_map, vec3(m.uv, windowDepth(dRef)));
#endif
}
#elif defined(MAP_MOMENTS)
// The moments at the point, bilinearly filtered (and blurred).
vec4 momentsAt(MapPoint m) {
    SO_TAP(MAP_FILTER_TEXELS, MAP_TEXEL_BYTES);
#ifdef LIGHT_CUBE
    return texture(u_map, m.v);
#elif defined(CASCADES)
    return texture(u_map, vec3(m.uv, float(g_cascade)));
#else
    return texture(u_map, m.uv);
#endif
}
// The one-sided Chebyshev bound, shared by the moment techniques.
float chebyshev(vec2 m, float t, float minVariance) {
    if (t <= m.x) return 1.0;
    float variance = max(m.y - m.x * m.x, minVariance);
    float d = t - m.x;
    return variance / (variance + d * d);
}
// Light-bleeding reduction: p below `amount` counts as shadow, the rest rescaled to [0, 1].
float reduceBleeding(float p, float amount) { return clamp((p - amount) / (1.0 - amount), 0.0, 1.0); }
#endif

#ifdef SCREEN_DERIVATIVES
// The receiver's position one pixel right and one up, less its own (receiver-plane, texel-plane):
// taken in main before any branch, where derivatives are defined.
vec3 g_dpdx, g_dpdy;
#endif

#ifdef RECEIVER_PLANE
// ---- The receiver's plane in the map (the receiver-plane, texel-plane, adaptive and oriented
// biases) ----
// Where q falls in m's map, in texels from m's own point, in the frame storedDepthAt's offsets
// use (2D maps: the map's texel grid; cube maps: m's face plane along m.t1, m.t2, m.step apart).
vec2 texelOffsetOf(MapPoint m, vec3 q) {
#ifdef LIGHT_CUBE
    vec3 axis = abs(m.v.x) >= abs(m.v.y) && abs(m.v.x) >= abs(m.v.z) ? vec3(sign(m.v.x), 0, 0)
                : abs(m.v.y) >= abs(m.v.z)                         ? vec3(0, sign(m.v.y), 0)
                                                                   : vec3(0, 0, sign(m.v.z));
    vec3 w = q - u_lsLightPosition;
    vec3 onFace = w * (m.d / max(dot(w, axis), 1e-30)) - m.v;
    return vec2(dot(onFace, m.t1), dot(onFace, m.t2)) / m.step;
#else
    return (mapPoint(q).uv - m.uv) * vec2(MAP_SIZE);
#endif
}
// The offset in texels (that frame) from m's point to the centre of the texel it looks up: where
// the map sampled whatever it holds there. Cube maps: the face and its s, t axes as GL 4.5's table
// 8.19 gives them.
vec2 ownTexelCentre(MapPoint m) {
#ifdef LIGHT_CUBE
    vec3 a = abs(m.v), sAxis, tAxis;
    if (a.x >= a.y && a.x >= a.z) sAxis = vec3(0, 0, -sign(m.v.x)), tAxis = vec3(0, -1, 0);
    else if (a.y >= a.z) sAxis = vec3(1, 0, 0), tAxis = vec3(0, 0, sign(m.v.y));
    else sAxis = vec3(sign(m.v.z), 0, 0), tAxis = vec3(0, -1, 0);
    vec2 st = 0.5 * (vec2(dot(m.v, sAxis), dot(m.v, tAxis)) / m.d + 1.0);
    float size = float(textureSize(u_map, 0).x);
    vec2 ds = (floor(st * size) + 0.5) / size - st;
    vec3 toCentre = 2.0 * m.d * (ds.x * sAxis + ds.y * tAxis);
    return vec2(dot(toCentre, m.t1), dot(toCentre, m.t2)) / m.step;
#else
    vec2 coord = m.uv * vec2(MAP_SIZE);
    return floor(coord) + 0.5 - coord;
#endif
}
// The offset in texels from m's point to the centre of the texel a tap o texels away reads: the
// texel centres lie at ownTexelCentre(m) plus whole texels, and a tap reads the one nearest it (o
// = 0: exactly ownTexelCentre(m)).
vec2 tapTexelCentre(MapPoint m, vec2 o) {
    vec2 own = ownTexelCentre(m);
    return own + floor(o - own + 0.5);
}
// The receiver's depth change per texel of offset, of the plane through p spanned by e1 and e2
// (world lengths about a texel: the differences are then well conditioned): the 2x2 system of
// where p + e1 and p + e2 fall and how deep they lie. An edge-on plane has none: huge.
vec2 receiverPlaneGradient(MapPoint m, vec3 p, vec3 e1, vec3 e2) {
    vec2 a = texelOffsetOf(m, p + e1), b = texelOffsetOf(m, p + e2);
    vec2 dd = vec2(receiverDepth(p + e1), receiverDepth(p + e2)) - m.d;
    float det = a.x * b.y - a.y * b.x;
    if (abs(det) < 1e-6 * length(a) * length(b)) return vec2(1e30);
    // g . a = dd.x, g . b = dd.y
    return vec2(dd.x * b.y - dd.y * a.y, a.x * dd.y - b.x * dd.x) / det;
}
// Two tangents of the receiver's plane, one texel long, from its geometric normal.
void planeTangents(Receiver r, out vec3 e1, out vec3 e2) {
    vec3 h = abs(r.n.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0);
    e1 = normalize(cross(r.n, h)) * r.texel;
    e2 = cross(r.n, e1);
}
// The depth gradient of the receiver's tangent plane (its geometric normal), per texel of offset
// (the adaptive and oriented biases).
vec2 tangentPlaneGradient(Receiver r, MapPoint m) {
    vec3 e1, e2;
    planeTangents(r, e1, e2);
    return receiverPlaneGradient(m, r.p, e1, e2);
}
#ifdef SCREEN_DERIVATIVES
// The depth gradient, per texel of offset, of the plane the receiver's screen-space derivatives
// span (Isidoro 2006; TheRealMJP/Shadows Mesh.hlsl:102-109, ComputeReceiverPlaneDepthBias, solves
// the same 2x2 system). A pixel's step can span many texels: the same plane, a texel long, keeps
// the projection's curvature (perspective maps) out of the differences.
vec2 screenPlaneGradient(Receiver r, MapPoint m) {
    vec3 e1 = g_dpdx * (r.texel / max(length(g_dpdx), 1e-30));
    vec3 e2 = g_dpdy * (r.texel / max(length(g_dpdy), 1e-30));
    return receiverPlaneGradient(m, r.p, e1, e2);
}
#endif
// The linear length at linear depth d that `w` of the map's window depth ([0, 1] from near to far,
// what the hardware stores and compares) spans toward the light: w (far - near) for an
// orthographic map, more the nearer d lies to the far plane for a perspective one.
float windowDepthLength(float d, float w) { return d - linearDepth(max(windowDepth(d) - w, 0.0)); }
// The rounding of what a receiver-plane comparison compares, as a length at linear depth d on a
// plane of gradient g (per texel): the stored depth (DEPTH_BITS, a 32-bit float's mantissa
// counting 24, through linearDepth's slope there), the receiver's own depth (a float: 2^-23 of
// it) and where it falls in the map (a float uv: 2^-23 of the map's side in texels, times the
// plane's slope: at a grazing light this term dominates); DEPTH_STEPS of their sum.
float depthPrecision(float d, vec2 g) {
    float step = exp2(-float(DEPTH_BITS)), ulp = exp2(-23.0);
#ifdef LIGHT_ORTHO
    float stored = step * (u_far - u_near);
#else
    float stored = step * d * d * (u_far - u_near) / (u_near * u_far);
#endif
    float where = (abs(g.x) + abs(g.y)) * ulp * float(textureSize(u_map, 0).x);
    return DEPTH_STEPS * (stored + ulp * abs(d) + where);
}
#endif  // RECEIVER_PLANE

// How many texels a filter's outer taps reach (the slope bias grows with it); a filter that reaches
// further defines it (pcf).
#ifndef BIAS_SPREAD
#define BIAS_SPREAD 1.0
#endif

// The slope-scaled bias (bias=slope, smrt, adaptive), as a length:
// clamp(alpha tan(theta), min, max) texels, times `spread` (a filter's outer taps see the
// receiver's plane that many texels deeper).
float slopeBias(Receiver r, float alpha, float minTexels, float maxTexels, float spread) {
    float tanTheta = sqrt(max(0.0, 1.0 - r.ndotl * r.ndotl)) / r.ndotl;
    return clamp(alpha * tanTheta, minTexels, maxTexels) * r.texel * spread;
}

#ifdef DEPTH_PROBE
void writeDepthProbe(vec3 p, float texel, float mapVisibility) {
    MapPoint m = mapPoint(p);
    float stored = m.outside ? uintBitsToFloat(0x7f800000u) : storedDepthAt(m, vec2(0.0));
    o_depthProbe = vec4(stored, m.d, texel, mapVisibility);
}
#endif

#ifdef CASCADES
// The cascade whose slice holds the point's view depth (the last beyond it); in the last `blend`
// of a slice, faded linearly into the next cascade's lookup so the seam does not show as a line.
float cascadedVisibility(vec3 p, vec3 n, float ndotl, float pixel) {
    float depth = dot(p - u_lsEye, u_lsCameraForward);
    int i = 0;
    while (i < CASCADES - 1 && depth > u_cascadeSplit[i + 1]) ++i;
    g_cascade = i;
    float texel = u_cascadeTexel[i];
    o_aliasing = (texel / max(ndotl, 1e-3)) / pixel;
    float v = techniqueVisibility(Receiver(p, n, ndotl, texel));
    float end = u_cascadeSplit[i + 1], band = u_cascadeBlend * (end - u_cascadeSplit[i]);
    if (i == CASCADES - 1 || band <= 0.0 || depth <= end - band) return v;
    g_cascade = i + 1;
    float next = techniqueVisibility(Receiver(p, n, ndotl, u_cascadeTexel[i + 1]));
    return mix(v, next, clamp((depth - (end - band)) / band, 0.0, 1.0));
}
#endif

void main() {
#ifdef SCREEN_DERIVATIVES
    g_dpdx = dFdx(v_lsPosition);
    g_dpdy = dFdy(v_lsPosition);
#endif
    alphaTest();
#ifdef DEPTH_PROBE
    o_depthProbe = vec4(-1.0, -1.0, 0.0, 0.0);
#endif
    vec3 p = v_lsPosition;
    vec3 n = normalize(v_lsFaceNormal);
    if (dot(n, p - u_lsEye) > 0.0) n = -n;
#ifdef LIGHT_ORTHO
    vec3 l = -u_lsLightDirection;
    float toLight = uintBitsToFloat(0x7f800000u);
#else
    vec3 l = normalize(u_lsLightPosition - p);
    float toLight = distance(u_lsLightPosition, p);
#endif
    float ndotl = dot(n, l);
    vec3 toEye = u_lsEye - p;
    float pixel = length(toEye) * u_pixelScale / max(abs(dot(n, normalize(toEye))), 1e-3);
    o_aliasing = 0.0;
    // The oracle's conventions: facing away, behind a one-sided emitter, or outside a spot's
    // cone, is unlit.
    if (ndotl <= 0.0) {
        o_visibility = 0.0;
        return;
    }
    // Behind a one-sided emitter (rect, disk: a light inside a room with surfaces above it).
    if (u_lsEmitNormal != vec3(0.0) && dot(u_lsEmitNormal, p - u_lsLightPosition) <= 0.0) {
        o_visibility = 0.0;
        return;
    }
#ifdef LIGHT_SPOT
    if (dot(-l, u_lsLightDirection) < u_cosOuter) {
        o_visibility = 0.0;
        return;
    }
#endif
#ifdef CASCADES
    float mapVisibility = cascadedVisibility(p, n, ndotl, pixel);
    float texel = u_cascadeTexel[g_cascade];  // the cascade looked up last
#else
    float texel = texelWorld(receiverDepth(p));
    o_aliasing = (texel / max(ndotl, 1e-3)) / pixel;
    float mapVisibility = techniqueVisibility(Receiver(p, n, ndotl, texel));
#endif
    o_visibility = mapVisibility;
#ifdef CONTACT
    if (mapVisibility > 0.0) o_visibility = mapVisibility * contactVisibility(p, l, toLight);
#endif
#ifdef DEPTH_PROBE
    writeDepthProbe(p, texel, mapVisibility);
#endif
}
