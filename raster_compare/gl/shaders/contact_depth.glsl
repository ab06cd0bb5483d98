// The camera's depth buffer as engines hold it, for the contact methods that read depth alone
// (contact_method=bevy, bend: contact_shadows.h), after shaders/shadow_map.frag and the technique's
// file. Reversed Z with an infinite far plane, as camera_pass.cpp projects: z/w = near / view
// depth, 1 at the near plane, 0 at infinity. The visibility pass shares the camera pass's depth
// attachment (its depth test), so it cannot also sample it; the value is recomputed from the
// surface point the camera pass stored at the pixel, which is the depth buffer's value up to float
// rounding. Nothing hit, or a texel outside the image, reads as the far plane, 0 (Bend's
// clamp-to-border sampler; Bevy clamps its reads to the image, contact_bevy.glsl). Each read is one
// position texel (16 bytes where an engine reads a 4-byte depth: the work counts say what is read).
uniform sampler2D u_contactPosition;
uniform mat4 u_clipFromLocal;  // the camera's (scene.vert's)

float contactDeviceDepth(ivec2 ij) {
    ivec2 size = textureSize(u_contactPosition, 0);
    if (any(lessThan(ij, ivec2(0))) || any(greaterThanEqual(ij, size))) return 0.0;
    SO_TAP(1, POSITION_TEXEL_BYTES);
    vec4 s = texelFetch(u_contactPosition, ij, 0);
    if (s.w < 0.5) return 0.0;
    vec4 c = u_clipFromLocal * vec4(s.xyz, 1.0);
    return c.z / c.w;
}

// The projected point of a local position: x, y in [-1, 1] over the image, z the depth above.
vec3 contactNdc(vec3 lsPoint) {
    vec4 c = u_clipFromLocal * vec4(lsPoint, 1.0);
    return c.xyz / c.w;
}
