// smrt's visibility frame over the adaptive (virtual) shadow map's pages (smrt:map=adaptive,
// techniques/smrt.cpp), after techniques/adaptive.glsl, shaders/taps.glsl and
// techniques/smrt_rays.glsl: V and the predicted aliasing of one light, with
// adaptive_visibility.frag's conventions (n.l <= 0 and outside a spot's cone: V = 0; beyond the
// map: V = 1). Each sample along a ray is looked up as adaptive looks up a receiver: in the finest
// resident page at or coarser than the level the receiver pixel needs, the bias in that level's
// texels. The mark pass asks for pages for the receivers only (as Unreal does), though a ray
// reaches points no receiver pixel asked for: a sample whose page is not resident at that level
// falls back to the finest resident page coarser than it (resident() walks up the levels). The
// coarsest level, one page over the whole map, is always resident, so no sample inside the map
// counts as unoccluded for want of a page.
layout(location = 0) out float o_visibility;
layout(location = 1) out float o_aliasing;

int g_level;  // the level the receiver pixel's footprint needs (main sets it)

HeightSample heightSample(vec3 q) {
    HeightSample s;
    VirtualPoint v = virtualPointAt(q);
    s.covered = !v.outside;
    if (!s.covered) return s;
    v.level = g_level;
    Resident r = resident(v);
    s.covered = r.slot >= 0;
    if (!s.covered) return s;
    s.d = v.d;
    s.texel = v.texel0 * exp2(float(r.level));
    s.stored = storedDepth(r.slot, r.texel);
    return s;
}

float mapDepth(vec3 q) { return -(u_lightViewFromLocal * vec4(q, 1.0)).z; }

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
    g_level = v.level;
    o_visibility = smrtVisibility(s.p, slopeBias(s, texel), texel);
}
