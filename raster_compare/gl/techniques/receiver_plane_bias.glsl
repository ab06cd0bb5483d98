// receiver-plane (receiver_plane_bias.cpp): the receiver's depth at its texel's centre, on the
// plane its screen-space derivatives span, less the depth buffer's rounding.
float techniqueVisibility(Receiver r) {
    MapPoint m = mapPoint(r.p);
    if (m.outside) return 1.0;
    vec2 g = receiverPlaneGradient(m, r.p, g_dpdx, g_dpdy);
    vec2 centre = ownTexelCentre(m);
    float dRef = m.d + dot(g, centre) - depthPrecision(m.d, g);
    return depthTap(m, ivec2(0), dRef);
}
