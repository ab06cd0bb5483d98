// Screen-space contact shadows, contact_method=guarded: our own design (contact_shadows.h;
// docs/techniques.md#contact), after shaders/shadow_map.frag and the technique's file. It reads
// the camera pass's mesh ids, which no engine's depth buffer has. CONTACT_STEPS samples along the
// ray from the receiver toward the light, u_contactDistance long (local units), the first one a
// per-pixel fraction of a step out (interleaved gradient noise, turned per frame with TEMPORAL) so
// that the steps' banding becomes noise. Each sample is projected into the camera pass's image: the
// surface seen there (u_contactPosition, w 1 where one was hit) shadows the sample when the sample
// lies behind it along the camera's ray by less than u_contactThickness (the depth buffer is
// taken to be that thick) and, where that surface is of the receiver's own mesh (the camera pass's
// mesh id, u_contactNormal's w), behind its tangent plane (its camera-facing normal): a receiver on
// a plane, or on a lit curved surface, is never shadowed by its own neighbouring pixels, whose
// centres lie at another depth than the sample's projection (the steep-slope self-shadowing of
// bevyengine/bevy 25355); another mesh's surface, the caster at a contact, shadows by depth alone
// (its tangent plane at a curved foot would turn the sample away). A sample beyond the image has
// no surface to be compared with: the march stops there, lit (a caster off screen casts no
// contact shadow).
// The ray stops at the light (maxLength). Binary: 0 or 1.
uniform sampler2D u_contactPosition;
uniform sampler2D u_contactNormal;
uniform float u_contactThickness;
uniform float u_contactDistance;
uniform mat4 u_clipFromLocal;  // the camera's (scene.vert's)

float contactVisibility(vec3 p, vec3 l, float maxLength) {
    float len = min(u_contactDistance, maxLength);
    float start = tapRotation() / 6.28318531;
    ivec2 size = textureSize(u_contactPosition, 0);
    SO_TAP(1, NORMAL_TEXEL_BYTES);
    float ownMesh = texelFetch(u_contactNormal, ivec2(gl_FragCoord.xy), 0).w;
    for (int i = 0; i < CONTACT_STEPS; ++i) {
        vec3 q = p + l * (len * (float(i) + start) / float(CONTACT_STEPS));
        vec4 c = u_clipFromLocal * vec4(q, 1.0);
        if (c.w <= 0.0) return 1.0;
        vec2 uv = c.xy / c.w * 0.5 + 0.5;
        if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) return 1.0;
        ivec2 ij = ivec2(uv * vec2(size));
        SO_TAP(1, POSITION_TEXEL_BYTES);
        vec4 s = texelFetch(u_contactPosition, ij, 0);
        if (s.w < 0.5) continue;  // the background: nothing there
        float behind = distance(q, u_lsEye) - distance(s.xyz, u_lsEye);
        if (behind <= 0.0 || behind >= u_contactThickness) continue;
        SO_TAP(1, NORMAL_TEXEL_BYTES);
        vec4 n = texelFetch(u_contactNormal, ij, 0);  // w: its mesh
        if (n.w != ownMesh || dot(q - s.xyz, n.xyz) < 0.0) return 0.0;
    }
    return 1.0;
}
