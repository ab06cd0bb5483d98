// adaptive-bias (adaptive_bias.cpp): the tangent plane's depth at the texel's centre (the light's
// ray through it meets the plane there), less the depth buffer's precision at that depth.
float techniqueVisibility(Receiver r) {
    MapPoint m = mapPoint(r.p);
    if (m.outside) return 1.0;
    vec3 e1, e2;
    planeTangents(r, e1, e2);
    vec2 g = receiverPlaneGradient(m, r.p, e1, e2);
    float dCentre = m.d + dot(g, ownTexelCentre(m));
    return depthTap(m, ivec2(0), dCentre - depthPrecision(dCentre, g));
}
