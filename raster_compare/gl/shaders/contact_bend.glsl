// Screen-space contact shadows, contact_method=bend (contact_shadows.h,
// docs/techniques.md#contact), after shaders/contact_depth.glsl: Bend Studio's screen-space
// shadows (Days Gone; Godot 4.7 follows it). File:line below are bend_sss_gpu.h and
// bend_sss_cpu.h v1.3 as vendored unchanged in PanosK92/SpartanEngine 516d17e4d
// (data/shaders/bend_sss_gpu.hlsl, runtime/Rendering/bend_sss_cpu.h). Everything is in the
// depth buffer's non-linear depth. The light is projected to the screen; from each pixel
// CONTACT_SAMPLES samples step one pixel at a time along the line toward that point (away from it
// when the light is behind the camera), major axis at pixel centres. Each sample's depth, pushed
// back by its step to the neighbour across the ray (unless that step is an edge), is brought into
// a space where all rays toward the light are parallel (divided by its distance to the light);
// the pixel is shadowed where a sample lies in front of its ray by about u_contactSurfaceThickness
// of its depth (a window of that width, sharpened by u_contactContrast). The first
// CONTACT_HARD_SAMPLES can each shadow fully; the rest are kept as the minimum of four
// interleaved sets and averaged, the last CONTACT_FADE_SAMPLES fading out.
//
// Bend's compute shader shares one ray among 64 pixels (a wavefront, depths in LDS); here each
// pixel marches its own ray through its centre: the same samples but for a sub-pixel shift of the
// minor-axis read positions (the deviation its provenance lists).
uniform float u_contactSurfaceThickness;
uniform float u_contactBilinearThreshold;
uniform float u_contactContrast;

// Reversed Z (contact_depth.glsl): far 0, near 1, so z_sign is -1 (bend_sss_gpu.h:261).
const float kBendFarDepth = 0.0, kBendZSign = -1.0;

// BuildDispatchList's light coordinate (bend_sss_cpu.h:79-90): the light's pixel position (GL's
// window coordinates, as the depth texels lie), its depth, and w's sign (1: in front of the
// camera, rays converge on it). A sun is the direction toward it, w 0.
vec4 bendLightCoordinate() {
#ifdef LIGHT_ORTHO
    vec4 h = u_clipFromLocal * vec4(-u_lsLightDirection, 0.0);
#else
    vec4 h = u_clipFromLocal * vec4(u_lsLightPosition, 1.0);
#endif
    const float fpLimit = 0.000002 * 64.0;  // its wave size
    float xyW = h.w;
    if (xyW >= 0.0 && xyW < fpLimit) xyW = fpLimit;
    else if (xyW < 0.0 && xyW > -fpLimit) xyW = -fpLimit;
    vec2 size = vec2(textureSize(u_contactPosition, 0));
    return vec4((h.xy / xyW * 0.5 + 0.5) * size, h.w == 0.0 ? 0.0 : h.z / h.w,
                h.w > 0.0 ? 1.0 : -1.0);
}

// One sample's shadowing depth, perspective-corrected (bend_sss_gpu.h:270-333 with
// BilinearSamplingOffsetMode false, 379-385): the depth at the sample's pixel and its neighbour on
// the minor axis toward the ray; unless that step is an edge, pushed back by it (a surface the ray
// might cross between the two casts from the further one).
float bendStoredDepth(vec2 xy, bool xMajor, float sampleDistance, float lightZ) {
    vec2 readXY = floor(xy);
    float bilinear = fract(xMajor ? xy.y : xy.x) - 0.5;
    int bias = bilinear > 0.0 ? 1 : -1;
    ivec2 offset = xMajor ? ivec2(0, bias) : ivec2(bias, 0);
    float depth = contactDeviceDepth(ivec2(readXY));
    float neighbour = contactDeviceDepth(ivec2(readXY) + offset);
    float thicknessScale = abs(kBendFarDepth - depth);
    bool edge = abs(depth - neighbour) > thicknessScale * u_contactBilinearThreshold;
#ifdef CONTACT_IGNORE_EDGES
    float edgeDepth = 1e20;  // edge_skip: out of every window
#else
    float edgeDepth = depth;
#endif
    float shadowing = edge ? edgeDepth : depth + abs(depth - neighbour) * kBendZSign;
    // Past the light (it is on screen, nearer than CONTACT_SAMPLES): no sample.
    return sampleDistance > 0.0 ? (shadowing - lightZ) / sampleDistance : 1e10;
}

float contactVisibility(vec3 p, vec3 l, float maxLength) {
    vec4 light = bendLightCoordinate();
    float direction = -light.w;  // -1: toward the light's point, 1: away (bend_sss_gpu.h:260)
    vec2 pixel = gl_FragCoord.xy;
    vec2 fromLight = pixel - light.xy;
    bool xMajor = abs(fromLight.x) > abs(fromLight.y);
    float pixelDistance = abs(xMajor ? fromLight.x : fromLight.y);  // major-axis pixels
    if (pixelDistance <= 0.0) return 1.0;                           // on the light's own point
    vec2 stepXY = fromLight / pixelDistance * direction;  // one major-axis pixel along the ray
    float startDepth = contactDeviceDepth(ivec2(pixel));
    // bend_sss_gpu.h:400-423: the window's scale, at least a minimum width near the light.
    float depthScale = min(pixelDistance + direction, 1.0 / u_contactSurfaceThickness) *
                       pixelDistance / abs(kBendFarDepth - startDepth);
    float start = (startDepth - light.z) / pixelDistance * depthScale - kBendZSign;
    float hardShadow = 1.0;
    vec4 shadow = vec4(1.0);
    // bend_sss_gpu.h:426-456: sample i is i + 1 pixels along.
    for (int i = 0; i < CONTACT_SAMPLES; ++i) {
        float k = float(i + 1);
        float stored = bendStoredDepth(pixel + stepXY * k, xMajor, pixelDistance + direction * k,
                                       light.z);
        float delta = abs(start - stored * depthScale);
        if (i < CONTACT_HARD_SAMPLES)
            hardShadow = min(hardShadow, delta);
        else if (i < CONTACT_SAMPLES - CONTACT_FADE_SAMPLES)
            shadow[i & 3] = min(shadow[i & 3], delta);
        else
            shadow[i & 3] = min(shadow[i & 3], delta + float(i + 1 - (CONTACT_SAMPLES -
                                                                      CONTACT_FADE_SAMPLES)) /
                                                               float(CONTACT_FADE_SAMPLES + 1) *
                                                               0.75);
    }
    // bend_sss_gpu.h:459-468: contrast, the four sets averaged, the hard samples' minimum.
    shadow = clamp(shadow * u_contactContrast + (1.0 - u_contactContrast), 0.0, 1.0);
    hardShadow = clamp(hardShadow * u_contactContrast + (1.0 - u_contactContrast), 0.0, 1.0);
    return min(hardShadow, dot(shadow, vec4(0.25)));
}
