// adaptive's mark frame (techniques/adaptive.cpp): drawn from the camera over a depth prepass
// (depth test EQUAL), so only the surfaces the camera sees count; each lit pixel adds one to the
// request count of the page its footprint needs (techniques/adaptive.glsl). The early depth test is
// required: without it a hidden fragment's store could happen before the test discards it.
// MARK_EDGES (the refine pass, after a first round of pages): a pixel asks only where the resident
// page that serves it is coarser than it needs and puts a shadow edge within EDGE_RADIUS texels of
// it (Fernando et al.'s edge refinement): the depth test of every texel around it, each against the
// receiver's plane at that texel, must agree with its own, else it asks.
layout(early_fragment_tests) in;
layout(r32ui, binding = 0) uniform coherent uimage2D u_requests;

#ifdef MARK_EDGES
// True where the resident pages settle the pixel's V. A tap in a page that is not resident at that
// level settles nothing.
bool settled(Shading s, VirtualPoint v, Resident r) {
    if (r.level <= v.level) return true;
    float texel = v.texel0 * exp2(float(r.level));
    float bias = slopeBias(s, texel);
    // The receiver's plane in the light's view: linear depth grows by dot(nv.xy, offset) / nv.z.
    vec3 nv = mat3(u_lightViewFromLocal) * s.n;
    float nz = nv.z >= 0.0 ? max(nv.z, 0.05) : min(nv.z, -0.05);
    vec2 f = v.uv * float(VIRTUAL_SIZE >> r.level);
    int size = VIRTUAL_SIZE >> r.level;
    bool first = true, litHere = false;
    for (int y = -EDGE_RADIUS; y <= EDGE_RADIUS; ++y)
        for (int x = -EDGE_RADIUS; x <= EDGE_RADIUS; ++x) {
            ivec2 t = clamp(r.texel + ivec2(x, y), ivec2(0), ivec2(size - 1));
            int slot = slotOf(t, r.level);
            if (slot < 0) return false;
            vec2 offset = (vec2(t) + 0.5 - f) * texel;
            float dRef = v.d + dot(nv.xy, offset) / nz;
            bool lit = dRef - bias <= storedDepth(slot, t);
            if (first) litHere = lit;
            else if (lit != litHere) return false;
            first = false;
        }
    return true;
}
#endif

void main() {
    alphaTest();
    Shading s = shade();
    if (!s.lit) return;
    VirtualPoint v = virtualPoint(s);
    if (v.outside) return;
#ifdef MARK_EDGES
    if (settled(s, v, resident(v))) return;
#endif
    imageAtomicAdd(u_requests, tableCell(levelTexel(v, v.level), v.level), 1u);
}
