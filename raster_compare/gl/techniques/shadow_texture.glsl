// shadow-texture (shadow_texture.cpp): the map holds opacity. Map pass: 1 wherever a caster is.
// Visibility: only on the receiver, 1 - opacity; elsewhere lit (no self-shadowing by design).
#ifdef MOMENTS_PASS
vec4 momentsOf(float t) { return vec4(1.0, 0.0, 0.0, 0.0); }
#else
uniform float u_meshId;
uniform float u_receiverMesh;
float techniqueVisibility(Receiver r) {
    if (u_meshId != u_receiverMesh) return 1.0;
    MapPoint m = mapPoint(r.p);
    // Beyond the texture, or behind the light (a projector's back-projection): no shadow.
    if (m.outside || m.d <= 0.0) return 1.0;
    return 1.0 - clamp(momentsAt(m).x, 0.0, 1.0);
}
#endif
