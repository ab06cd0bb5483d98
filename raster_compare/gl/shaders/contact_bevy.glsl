// Screen-space contact shadows, contact_method=bevy (contact_shadows.h,
// docs/techniques.md#contact), after shaders/contact_depth.glsl: Bevy 0.19's (PR 22382), which
// calls its SSR ray marcher. File:line below are bevyengine/bevy at 4805ca79:
// crates/bevy_pbr/src/render/pbr_functions.wesl (calculate_contact_shadow, 288-322) and
// crates/bevy_pbr/src/ssr/raymarch.wesl (Stachowiak's depth_ray_march_*). The march runs in
// normalized device coordinates from the receiver to the receiver plus u_contactDistance toward
// the light, clipped to the view, in CONTACT_STEPS screen-space linear steps (fewer where the ray
// spans fewer pixels), the first a jitter of a step out (interleaved gradient noise of the pixel
// and frame % 64). A sample occludes when it lies below both the point-sampled and the bilinear
// depth, by less than u_contactThickness of linear view depth (the buffer's surfaces taken to be
// that thick); the first such sample ends the march, and V is
// clamp((penetration / thickness - 0.5) / 0.5, 0, 1): lit again as the ray nears the thickness.
uniform float u_contactThickness;  // world units of view depth
uniform float u_contactDistance;   // local units

// The depth at a texel clamped to the image (raymarch.wesl:35-40).
float bevyDepthTexel(ivec2 t) {
    return contactDeviceDepth(clamp(t, ivec2(0), textureSize(u_contactPosition, 0) - 1));
}

// Bilinear and nearest depth at uv, by texel reads as Bevy's mesh pass takes them
// (raymarch.wesl:43-63: depth_sample_nearest_clamped, depth_sample_bilinear_clamped).
float bevyDepthNearest(vec2 uv) {
    vec2 coord = uv * vec2(textureSize(u_contactPosition, 0)) - 0.5;
    return bevyDepthTexel(ivec2(floor(coord + 0.5)));
}
float bevyDepthLinear(vec2 uv) {
    vec2 coord = uv * vec2(textureSize(u_contactPosition, 0)) - 0.5;
    ivec2 base = ivec2(floor(coord));
    vec2 f = coord - floor(coord);
    float d0 = mix(bevyDepthTexel(base), bevyDepthTexel(base + ivec2(1, 0)), f.x);
    float d1 = mix(bevyDepthTexel(base + ivec2(0, 1)), bevyDepthTexel(base + ivec2(1, 1)), f.x);
    return mix(d0, d1, f.y);
}

// 1 / depth: linear view depth over the near plane's (Bevy's "scaled linear z"); the far plane,
// depth 0, is infinitely far.
float bevyScaledLinear(float depth) {
    return depth > 0.0 ? 1.0 / depth : uintBitsToFloat(0x7f800000u);
}

// depth_raymarch_distance_fn_evaluate (raymarch.wesl:260-319), march_behind_surfaces on, not
// sloppy: x the signed distance to the surface below both depths (< 0: under it), y the
// penetration below the nearer of the two; valid while that is within the thickness.
vec2 bevyDistance(vec3 ndc, float thickness) {
    vec2 uv = ndc.xy * 0.5 + 0.5;
    float rayDepth = 1.0 / ndc.z;
    float linearDepth = bevyScaledLinear(bevyDepthLinear(uv));
    float unfilteredDepth = bevyScaledLinear(bevyDepthNearest(uv));
    float maxDepth = max(linearDepth, unfilteredDepth), minDepth = min(linearDepth, unfilteredDepth);
    const float bias = 0.000002;
    return vec2(maxDepth * (1.0 + bias) - rayDepth, rayDepth - minDepth);
}

// depth_ray_march_to_cs and _to_cs_dir_impl (raymarch.wesl:425-474): the ray's end point, start
// and end clipped to the view (x, y in [-1, 1], z in [0, 1]).
void bevyClipRay(inout vec3 startNdc, vec3 endNdc, out vec3 clippedEnd) {
    vec4 dir = vec4(endNdc - startNdc, 0.0) * sign(endNdc.z);
    vec4 endCs = vec4(startNdc, 1.0) + dir;
    endCs /= (endCs.w >= 0.0 ? 1.0 : -1.0) * max(1e-10, abs(endCs.w));
    vec3 delta = endCs.xyz - startNdc;
    vec3 nearEdge = mix(vec3(-1.0, -1.0, 0.0), vec3(1.0), lessThan(delta, vec3(0.0)));
    vec3 toNear = (nearEdge - startNdc) / delta;
    startNdc += delta * max(0.0, max(toNear.x, toNear.y));
    delta = endCs.xyz - startNdc;
    vec3 farEdge = mix(vec3(-1.0, -1.0, 0.0), vec3(1.0), greaterThanEqual(delta, vec3(0.0)));
    vec3 toFar = (farEdge - startNdc) / delta;
    delta *= min(1.0, min(min(toFar.x, toFar.y), toFar.z));
    clippedEnd = startNdc + delta;
}

// utils.wesl:45-48 (interleaved_gradient_noise), at Bevy's frag_coord (y down from the top), of
// the sequence's frame (u_frameIndex, shaders/taps.glsl): Bevy's default build has no blue-noise
// texture (pbr_functions.wesl:306-307).
float bevyJitter() {
    vec2 pixel = vec2(gl_FragCoord.x, float(textureSize(u_contactPosition, 0).y) - gl_FragCoord.y);
    vec2 xy = pixel + 5.588238 * float(u_frameIndex % 64);
    return fract(52.9829189 * fract(0.06711056 * xy.x + 0.00583715 * xy.y));
}

float contactVisibility(vec3 p, vec3 l, float maxLength) {
    vec3 start = contactNdc(p), end;  // Bevy's ray has no stop at the light: maxLength unused
    bevyClipRay(start, contactNdc(p + l * u_contactDistance), end);
    // depth_ray_march_march (raymarch.wesl:498-549): at least 2 steps, at most one a pixel.
    vec2 lengthPx = (end.xy - start.xy) * 0.5 * vec2(textureSize(u_contactPosition, 0));
    int steps = max(2, min(CONTACT_STEPS, int(floor(length(lengthPx)))));
    // The thickness in scaled linear depth (raymarch.wesl:513-514); clip.z is the near plane's
    // distance for every point (camera_pass.cpp).
    float thickness = u_contactThickness / u_clipFromLocal[3][2];
    float jitter = bevyJitter();
    // hybrid_root_finder_find_root's linear search (raymarch.wesl:128-178): no bisection, no
    // secant, exponent 1, as calculate_contact_shadow leaves them.
    for (int i = 0; i < steps; ++i) {
        vec2 d = bevyDistance(mix(start, end, (float(i) + jitter) / float(steps)), thickness);
        if (d.x < 0.0 && d.y < thickness)  // intersected and valid (raymarch.wesl:163, 313)
            // A hit (raymarch.wesl:543-548), its penetration as a fraction of the thickness;
            // pbr_functions.wesl:318-320.
            return clamp((d.y / thickness - 0.5) / (1.0 - 0.5), 0.0, 1.0);
    }
    return 1.0;
}
