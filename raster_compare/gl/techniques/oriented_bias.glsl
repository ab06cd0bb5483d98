// oriented-bias (oriented_bias.cpp): the bias the receiver's tangent plane needs over half a texel
// along each map axis, plus the depth buffer's rounding.
float techniqueVisibility(Receiver r) {
    MapPoint m = mapPoint(r.p);
    if (m.outside) return 1.0;
    vec3 e1, e2;
    planeTangents(r, e1, e2);
    vec2 g = receiverPlaneGradient(m, r.p, e1, e2);
    return depthTap(m, ivec2(0), m.d - 0.5 * (abs(g.x) + abs(g.y)) - depthPrecision(m.d, g));
}
