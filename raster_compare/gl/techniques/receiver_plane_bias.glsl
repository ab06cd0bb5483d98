// receiver-plane (receiver_plane_bias.cpp): the receiver's depth at its texel's centre, on the
// plane its screen-space derivatives span, less the depth buffer's rounding.
float techniqueVisibility(Receiver r) {
    MapPoint m = mapPoint(r.p);
    if (m.outside) return 1.0;
    // A pixel's step can span many texels: the same plane, a texel long, keeps the projection's
    // curvature (perspective maps) out of the differences.
    vec3 e1 = g_dpdx * (r.texel / max(length(g_dpdx), 1e-30));
    vec3 e2 = g_dpdy * (r.texel / max(length(g_dpdy), 1e-30));
    vec2 g = receiverPlaneGradient(m, r.p, e1, e2);
    vec2 centre = ownTexelCentre(m);
    float dRef = m.d + dot(g, centre) - depthPrecision(m.d, g);
    return depthTap(m, ivec2(0), dRef);
}
