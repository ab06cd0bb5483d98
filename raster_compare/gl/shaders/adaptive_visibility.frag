// adaptive's visibility frame (techniques/adaptive.cpp): V and the predicted aliasing of one light,
// with shadow_map.frag's conventions (n faces the eye; n.l <= 0 and outside a spot's cone: V = 0;
// beyond the map: V = 1). The point is looked up in the finest resident page at or coarser than the
// level its footprint needs, then depth-tested as slope-bias does (the bias in texels of the level
// used), comparing linear depths.
layout(location = 0) out float o_visibility;
layout(location = 1) out float o_aliasing;

void main() {
    alphaTest();
    Shading s = shade();
    o_aliasing = 0.0;
    if (!s.lit) {
        o_visibility = 0.0;
        return;
    }
    VirtualPoint v = virtualPoint(s);
    Resident r = Resident(v.level, -1, ivec2(0));
    if (!v.outside) r = resident(v);
    float texel = v.texel0 * exp2(float(r.level));
    o_aliasing = (texel / max(s.ndotl, 1e-3)) / s.pixel;
    if (v.outside || r.slot < 0) {
        o_visibility = 1.0;
        return;
    }
    o_visibility = v.d - slopeBias(s, texel) <= storedDepth(r.slot, r.texel) ? 1.0 : 0.0;
}
