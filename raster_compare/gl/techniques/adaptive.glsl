// adaptive (adaptive.cpp): what its mark frame (shaders/adaptive_mark.frag) and visibility frame
// (shaders/adaptive_visibility.frag), and smrt's frame over the same pages
// (shaders/smrt_virtual.frag), share, so all pick the same page for a pixel: the receiver
// as shadow_map.frag's main sees it, the level of the virtual map its footprint needs, the level's
// texel and page, the resident page that serves it and the slope-scaled depth test. Defines:
// LIGHT_ORTHO or LIGHT_SPOT; VIRTUAL_SIZE, PAGE_SIZE, LEVELS, DENSITY (texels wanted across the
// pixel's footprint, at n.l), POOL_COLUMNS; SLOPE_FACTOR, SLOPE_MIN, SLOPE_MAX (slope-bias's);
// TABLE_TEXEL_BYTES, POOL_TEXEL_BYTES (the work counts' SO_TAP).
in vec3 v_lsPosition;
flat in vec3 v_lsFaceNormal;
uniform vec3 u_lsEye;
uniform float u_pixelScale;  // camera pixel size per unit of distance
uniform vec3 u_lsLightPosition;
uniform vec3 u_lsLightDirection;  // the way light travels
uniform float u_cosOuter;
uniform mat4 u_lightClipFromLocal;  // the whole virtual map (level 0)
uniform mat4 u_lightViewFromLocal;
uniform float u_near;
uniform float u_far;
uniform float u_texelScale;  // level 0; ortho: texel size; spot: per unit of depth
uniform int u_levelRow[LEVELS];  // each level's first row in the page table
uniform isampler2D u_pageTable;  // per cell: the pool slot, or -1
uniform sampler2D u_pool;        // the physical pages, POOL_COLUMNS a row, window depth

// The receiver, with shadow_map.frag's conventions: n faces the eye; `lit` false where the light
// cannot reach (n.l <= 0, outside a spot's cone); pixel: the camera pixel's footprint there.
struct Shading {
    vec3 p;
    vec3 n;
    float ndotl;
    float pixel;
    bool lit;
};

Shading shade() {
    Shading s;
    s.p = v_lsPosition;
    s.n = normalize(v_lsFaceNormal);
    if (dot(s.n, s.p - u_lsEye) > 0.0) s.n = -s.n;
#ifdef LIGHT_ORTHO
    vec3 l = -u_lsLightDirection;
#else
    vec3 l = normalize(u_lsLightPosition - s.p);
#endif
    s.ndotl = dot(s.n, l);
    vec3 toEye = u_lsEye - s.p;
    s.pixel = length(toEye) * u_pixelScale / max(abs(dot(s.n, normalize(toEye))), 1e-3);
    s.lit = s.ndotl > 0.0;
#ifdef LIGHT_SPOT
    if (dot(-l, u_lsLightDirection) < u_cosOuter) s.lit = false;
#endif
    return s;
}

// Where a point falls in the virtual map: uv over the whole map, its linear depth d, level 0's
// texel size there, and the level it is looked up at.
struct VirtualPoint {
    bool outside;
    vec2 uv;
    float d;
    float texel0;
    int level;
};

// Any point (smrt's samples along a ray: shaders/smrt_virtual.frag), at level 0.
VirtualPoint virtualPointAt(vec3 p) {
    VirtualPoint v;
    vec4 c = u_lightClipFromLocal * vec4(p, 1.0);
    v.uv = c.xy / c.w * 0.5 + 0.5;
    v.d = -(u_lightViewFromLocal * vec4(p, 1.0)).z;
    v.outside = any(lessThan(v.uv, vec2(0.0))) || any(greaterThan(v.uv, vec2(1.0))) || v.d > u_far;
#ifdef LIGHT_ORTHO
    v.texel0 = u_texelScale;
#else
    v.texel0 = v.d * u_texelScale;
#endif
    v.level = 0;
    return v;
}

// The receiver, at the level it needs: the coarsest whose texel is at most pixel * n.l / DENSITY,
// which keeps the predicted aliasing (texel / n.l) / pixel at or below 1 / DENSITY.
VirtualPoint virtualPoint(Shading s) {
    VirtualPoint v = virtualPointAt(s.p);
    float wanted = s.pixel * max(s.ndotl, 1e-3) / DENSITY;
    v.level = int(clamp(floor(log2(wanted / v.texel0)), 0.0, float(LEVELS - 1)));
    return v;
}

// The point's texel in `level` (texel coordinates over the whole level).
ivec2 levelTexel(VirtualPoint v, int level) {
    int size = VIRTUAL_SIZE >> level;
    return clamp(ivec2(floor(v.uv * float(size))), ivec2(0), ivec2(size - 1));
}

// The page table cell of the page holding a texel of `level`.
ivec2 tableCell(ivec2 texel, int level) {
    ivec2 page = texel / PAGE_SIZE;
    return ivec2(page.x, u_levelRow[level] + page.y);
}

// The pool slot of the page holding a texel of `level`, or -1.
int slotOf(ivec2 texel, int level) {
    SO_TAP(1, TABLE_TEXEL_BYTES);
    return texelFetch(u_pageTable, tableCell(texel, level), 0).r;
}

// The page that serves a point: the finest resident at or coarser than its level (the coarsest
// level is always resident), and the point's texel there.
struct Resident {
    int level;
    int slot;
    ivec2 texel;
};

Resident resident(VirtualPoint v) {
    Resident r;
    for (r.level = v.level; r.level < LEVELS; ++r.level) {
        r.texel = levelTexel(v, r.level);
        r.slot = slotOf(r.texel, r.level);
        if (r.slot >= 0) break;
    }
    return r;
}

float linearDepth(float z) {
#ifdef LIGHT_ORTHO
    return u_near + z * (u_far - u_near);
#else
    return u_near * u_far / (u_far - z * (u_far - u_near));
#endif
}

// The linear depth stored for a texel of a resident page.
float storedDepth(int slot, ivec2 texel) {
    ivec2 origin = ivec2(slot % POOL_COLUMNS, slot / POOL_COLUMNS) * PAGE_SIZE;
    SO_TAP(1, POOL_TEXEL_BYTES);
    return linearDepth(texelFetch(u_pool, origin + texel % PAGE_SIZE, 0).r);
}

// slope-bias's bias as a length, for a texel of that size.
float slopeBias(Shading s, float texel) {
    float tanTheta = sqrt(max(0.0, 1.0 - s.ndotl * s.ndotl)) / s.ndotl;
    return clamp(SLOPE_FACTOR * tanTheta, SLOPE_MIN, SLOPE_MAX) * texel;
}
