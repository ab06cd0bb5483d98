// Taps that turn per pixel and per frame, for any visibility frame that samples around a point: the
// shadow-map family's (shaders/shadow_map.frag: pcf, pcss, smrt, contact shadows) and smrt's over
// the virtual map (shaders/smrt_virtual.frag). Comes before them.
// Taps that turn per pixel (pcss's pattern=rotated) and, with TEMPORAL (temporal=on of pcf and
// pcss, docs/techniques.md#temporal), per frame: interleaved gradient noise (Jimenez 2014) at the
// pixel, the pixel moved by 5.588238 per frame (u_frameIndex, the sequence's frame), the frame
// term Bevy (utils.wesl interleaved_gradient_noise, frame % 64) and Godot 4 (quick_hash with
// taa_frame_count) add, as an angle in [0, 2 pi). three.js r182+ (PCFShadowMap) turns its taps by
// the pixel's noise alone, with no frame term, and accumulates nothing (pcf's pattern=three).
uniform int u_frameIndex;
float interleavedGradientNoise(vec2 pixel) {
    return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}
float tapRotation() {
    vec2 pixel = gl_FragCoord.xy;
#ifdef TEMPORAL
    // The frame wraps where Bevy wraps it (utils.wgsl:73, frame % 64): this frame term is Bevy's.
    pixel += 5.588238 * float(u_frameIndex % 64);
#endif
    return 6.28318531 * interleavedGradientNoise(pixel);
}
// Tap k of n on a Vogel disk: a golden-angle spiral filling the unit disk evenly, turned by
// `rotation` radians.
vec2 vogelTap(int k, int n, float rotation) {
    float r = sqrt((float(k) + 0.5) / float(n));
    float a = float(k) * 2.39996323 + rotation;
    return r * vec2(cos(a), sin(a));
}
