#include "oracle/hard_shadow.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>

#include <tbb/combinable.h>
#include <glm/geometric.hpp>

#include "core/lights/light_kind.h"
#include "core/progress.h"
#include "oracle/exact_facing.h"
#include "oracle/offset.h"
#include "oracle/sse_lanes.h"
#include "oracle/tile_rows.h"

namespace so {

namespace {
// A float value this close to a boundary may lie on either side of it by rounding: the lane is
// decided exactly (resolveTies). The bounds are upper bounds of the float error, with margin (8x
// and 4x). The cosine n.w of a positional light: the normal and the unit direction carry ~2^-24
// each and the arithmetic a few ulp (under 2^-21 together); the surface point and the light's
// position are rounded to float, |dp| < 2^-24 (|p| < 1 in the local frame) and |dl| < 2^-24 |l|,
// which moves the cosine by up to (|dp| + |dl|) / dist.
constexpr float kTieCos = 1.0f / 262144.0f;        // 2^-18
constexpr float kTiePosition = 1.0f / 1048576.0f;  // 2^-20, times (1 + |l|)

// The packet loops' clones (setupPacket, traceTile): see setupPacket.
#ifndef SO_HARD_CLONES  // -DSO_HARD_CLONES= builds the default clone alone (a check of the bits)
#define SO_HARD_CLONES __attribute__((target_clones("avx2", "default")))
#endif

}  // namespace

HardLight makeHardLight(const Light& light, const LocalFrame& frame) {
    HardLight h;
    h.ws = light;
    // Without the penumbra effect an area light is traced as a point light at its centre; rect,
    // disk and polygon lights still emit on one side only.
    h.directional = isDirectional(light);
    h.spot = hasCone(light);
    h.oneSided = isOneSided(light);
    if (h.oneSided) h.lsEmitNormalF = glm::vec3(light.wsEmitNormal());
    h.lsPosition = frame.lsFromWs(light.wsPosition);
    h.lsDirection = glm::normalize(light.wsDirection);
    if (h.spot) h.cosOuter = std::cos(light.outerConeDeg * std::numbers::pi / 180.0);
    if (!h.directional) h.lsEndMargin = offsetMargin(glm::vec3(h.lsPosition));
    h.lsPositionF = glm::vec3(h.lsPosition);
    h.lsDirectionF = glm::vec3(h.lsDirection);
    h.cosOuterF = float(h.cosOuter);
    const glm::dvec3 a = glm::abs(h.lsPosition);
    h.lsTieScale = float(kTiePosition * (1.0 + std::max({a.x, a.y, a.z})));
    return h;
}

namespace {

// Per-lane values the classification needs beyond PacketSetup.
struct LaneScratch {
    alignas(64) float spotCos[16];
    alignas(64) float behindDot[16];  // one-sided emitters: > 0 where p is on the emitting side
    alignas(64) float tieCos[16];     // |cosine| below this: decide exactly
    alignas(64) float tieBehind[16];  // |behindDot| below this: decide exactly
};

[[gnu::always_inline]] inline void setupDirectional(const HardLight& light, PacketSetup& ps,
                                                    LaneScratch& ls, const float* nx,
                                                    const float* ny, const float* nz) {
    const glm::vec3 d = light.lsDirectionF;
    for (int k = 0; k < 16; ++k) {
        ps.cosine[k] = -(nx[k] * d.x + ny[k] * d.y + nz[k] * d.z);
        ps.dirX[k] = -d.x;
        ps.dirY[k] = -d.y;
        ps.dirZ[k] = -d.z;
        ps.tfar[k] = std::numeric_limits<float>::infinity();
        ls.spotCos[k] = 1.0f;
        ls.behindDot[k] = 1.0f;
        ls.tieCos[k] = kTieCos;
        ls.tieBehind[k] = 0.0f;
    }
}

// From the surface point, not the offset origin: the origin sits above the surface along the
// normal, which at grazing incidence would lower the cosine by as much as the cosine itself. The
// ray, aimed along this direction from the offset origin, ends within the offset of the light,
// which the doubled margin allows.
// kOneSided: the emitter-side values, which point and spot lights do not need.
template <bool kOneSided>
[[gnu::always_inline]] inline void setupPositional(const HardLight& light, const SurfaceBuffer& sb,
                                                   size_t base, PacketSetup& ps, LaneScratch& ls) {
    const float* px = &sb.lsPointX[base];
    const float* py = &sb.lsPointY[base];
    const float* pz = &sb.lsPointZ[base];
    const float* nx = &sb.lsNormalX[base];
    const float* ny = &sb.lsNormalY[base];
    const float* nz = &sb.lsNormalZ[base];
    const glm::vec3 l = light.lsPositionF, d = light.lsDirectionF, e = light.lsEmitNormalF;
    const float endMargin = 2.0f * light.lsEndMargin;
    const float tiePosition = light.lsTieScale;
    for (int k = 0; k < 16; ++k) {
        const float tx = l.x - px[k], ty = l.y - py[k], tz = l.z - pz[k];
        const float dist = std::sqrt(tx * tx + ty * ty + tz * tz);
        const float inv = 1.0f / dist;
        const float wx = tx * inv, wy = ty * inv, wz = tz * inv;
        ps.cosine[k] = nx[k] * wx + ny[k] * wy + nz[k] * wz;
        ls.spotCos[k] = -(wx * d.x + wy * d.y + wz * d.z);
        ps.dirX[k] = wx;
        ps.dirY[k] = wy;
        ps.dirZ[k] = wz;
        ps.tfar[k] = std::max(0.0f, dist - endMargin);
        // inv is +inf at the light itself: the lane is then a tie, decided exactly.
        ls.tieCos[k] = kTieCos + tiePosition * inv;
        if constexpr (kOneSided) {
            ls.behindDot[k] = -(e.x * tx + e.y * ty + e.z * tz);
            ls.tieBehind[k] = kTieCos * dist + tiePosition;
        } else {
            ls.behindDot[k] = 1.0f;
            ls.tieBehind[k] = 0.0f;
        }
    }
}

// Four groups of four 32-bit lane masks (-1 or 0) as 16 bytes, in lane order.
__m128i packLaneMasks(const __m128* m) {
    return _mm_packs_epi16(_mm_packs_epi32(_mm_castps_si128(m[0]), _mm_castps_si128(m[1])),
                           _mm_packs_epi32(_mm_castps_si128(m[2]), _mm_castps_si128(m[3])));
}
// Byte lanes: `a` where mask, else `b`.
__m128i selectBytes(__m128i mask, ShadowRayKind a, __m128i b) {
    return _mm_or_si128(_mm_and_si128(mask, _mm_set1_epi8(char(a))), _mm_andnot_si128(mask, b));
}

// Every lane's kind, its cosine zeroed where the primary ray missed, and the lanes whose float
// test is a tie as a bit mask, in SSE2 over four lanes at a time (the compiler leaves these
// byte-and-float loops lane by lane). NaN compares false: a NaN cosine (a point at the light
// itself) faces away, and is a tie.
template <bool kOneSided>
[[gnu::always_inline]] inline uint32_t classifyPacket(const SurfaceBuffer& sb, size_t base,
                                                      const HardLight& light, const LaneScratch& ls,
                                                      PacketSetup& ps) {
    const bool spot = light.spot;
    const __m128i missBytes = _mm_cmpeq_epi8(
        _mm_loadu_si128(reinterpret_cast<const __m128i*>(&sb.hit[base])), _mm_setzero_si128());
    const __m128i missLo = _mm_unpacklo_epi8(missBytes, missBytes),
                  missHi = _mm_unpackhi_epi8(missBytes, missBytes);
    const __m128i miss32[4] = {
        _mm_unpacklo_epi16(missLo, missLo), _mm_unpackhi_epi16(missLo, missLo),
        _mm_unpacklo_epi16(missHi, missHi), _mm_unpackhi_epi16(missHi, missHi)};
    const __m128 absMask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
    __m128 facing[4], outside[4], behind[4], tie[4];
    for (int g = 0; g < 4; ++g) {
        const __m128 c = _mm_load_ps(ps.cosine + 4 * g);
        facing[g] = _mm_cmpgt_ps(c, _mm_setzero_ps());
        outside[g] =
            spot ? _mm_cmplt_ps(_mm_load_ps(ls.spotCos + 4 * g), _mm_set1_ps(light.cosOuterF))
                 : _mm_setzero_ps();
        tie[g] = _mm_cmpnge_ps(_mm_and_ps(c, absMask), _mm_load_ps(ls.tieCos + 4 * g));
        if constexpr (kOneSided) {
            const __m128 d = _mm_load_ps(ls.behindDot + 4 * g);
            behind[g] = _mm_cmpngt_ps(d, _mm_setzero_ps());
            tie[g] = _mm_or_ps(
                tie[g], _mm_cmpnge_ps(_mm_and_ps(d, absMask), _mm_load_ps(ls.tieBehind + 4 * g)));
        } else {
            behind[g] = _mm_setzero_ps();
        }
        _mm_store_ps(ps.cosine + 4 * g, _mm_andnot_ps(_mm_castsi128_ps(miss32[g]), c));
    }
    __m128i kinds = _mm_set1_epi8(char(ShadowRayKind::Traced));
    kinds = selectBytes(packLaneMasks(behind), ShadowRayKind::BehindLight, kinds);
    kinds = selectBytes(packLaneMasks(outside), ShadowRayKind::OutsideCone, kinds);
    kinds = selectBytes(_mm_xor_si128(packLaneMasks(facing), _mm_set1_epi8(-1)),
                        ShadowRayKind::Attached, kinds);
    kinds = selectBytes(missBytes, ShadowRayKind::Background, kinds);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(ps.kind), kinds);
    return uint32_t(_mm_movemask_epi8(_mm_andnot_si128(missBytes, packLaneMasks(tie))));
}

ShadowRayKind laneKind(bool facing, bool outsideCone, bool behind) {
    return !facing       ? ShadowRayKind::Attached
           : outsideCone ? ShadowRayKind::OutsideCone
           : behind      ? ShadowRayKind::BehindLight
                         : ShadowRayKind::Traced;
}

// The lanes in `ties`, decided on the scene's doubles (exact_facing.h). The cosine keeps its
// magnitude and takes the exact sign (0 where the light is exactly in the plane), so that the
// cos channel's sign always agrees with the decision.
void resolveTies(const Accel& accel, const SurfaceBuffer& sb, size_t base, const HardLight& light,
                 uint32_t ties, const LaneScratch& ls, PacketSetup& ps) {
    const bool spot = light.spot;
    for (int k = 0; k < 16; ++k) {
        if (!(ties >> k & 1u)) continue;
        const size_t slot = base + size_t(k);
        FacingCache& cache = ps.facingCache;
        if (cache.triangle != sb.originId[slot]) {
            const PixelTriangle t = pixelTriangle(accel, sb, slot);
            cache.triangle = sb.originId[slot];
            cache.facing = int8_t(light.directional ? facingDirection(t, -light.ws.wsDirection)
                                                    : facingPoint(t, light.ws.wsPosition));
            cache.emitter = int8_t(light.oneSided ? emitterSide(t, light.ws) : 1);
        }
        ++ps.exactDecisions;
        // A float cosine of 0 with a non-zero exact sign becomes the smallest normal float.
        const float magnitude =
            std::max(std::fabs(ps.cosine[k]), std::numeric_limits<float>::min());
        ps.cosine[k] = float(cache.facing) * magnitude;
        const bool behind = cache.emitter == 0 ? !(ls.behindDot[k] > 0.0f) : cache.emitter < 0;
        ps.kind[k] = laneKind(cache.facing > 0, spot && ls.spotCos[k] < light.cosOuterF,
                              light.oneSided && behind);
    }
}

// The packet's setup, inlined into both of its callers' clones (below).
[[gnu::always_inline]] inline void setupPacketLanes(const Accel& accel, const SurfaceBuffer& sb,
                                                    size_t base, const HardLight& light,
                                                    PacketSetup& ps) {
    // Branch-free loops over the 16 lanes, so the compiler vectorises them: this setup runs once
    // per shadow ray and is what separates the oracle from a bare Embree loop (bench/).
    LaneScratch ls;
    if (light.directional)
        setupDirectional(light, ps, ls, &sb.lsNormalX[base], &sb.lsNormalY[base],
                         &sb.lsNormalZ[base]);
    else
        light.oneSided ? setupPositional<true>(light, sb, base, ps, ls)
                       : setupPositional<false>(light, sb, base, ps, ls);
    const uint32_t ties = light.oneSided ? classifyPacket<true>(sb, base, light, ls, ps)
                                         : classifyPacket<false>(sb, base, light, ls, ps);
    if (ties) resolveTies(accel, sb, base, light, ties, ls, ps);
}

}  // namespace

// Once for AVX2 (eight lanes at a time) and once for any x86-64, chosen at run time: neither
// enables fused multiply-add and every operation rounds the same IEEE way, so both give the same
// bits (the oracle's determinism does not depend on the CPU).
SO_HARD_CLONES void setupPacket(const Accel& accel, const SurfaceBuffer& sb, size_t base,
                                const HardLight& light, PacketSetup& ps) {
    setupPacketLanes(accel, sb, base, light, ps);
}

ShadowRaySetup setupShadowRay(const Accel& accel, const SurfaceBuffer& sb, size_t slot,
                              const HardLight& light) {
    // Through the packet code, so the benchmark's plain loops trace exactly the oracle's rays.
    PacketSetup ps;
    const size_t base = slot - slot % 16;
    setupPacket(accel, sb, base, light, ps);
    const int k = int(slot % 16);
    ShadowRaySetup s;
    s.kind = ps.kind[k];
    s.cosine = ps.cosine[k];
    s.org = sb.lsRayOrigin(slot);
    s.dir = {ps.dirX[k], ps.dirY[k], ps.dirZ[k]};
    s.tfar = ps.tfar[k];
    return s;
}

namespace {

// One thread's packet, reused tile after tile. The lanes' constant fields are set once: Embree
// writes only tfar (and the hit, for rtcIntersect16).
struct HardPacket {
    ShadowContext ctx;
    alignas(64) RTCRayHit16 rayHit;
    alignas(64) int valid[16];
    PacketSetup ps;
    uint64_t counts[int(ShadowRayKind::Count)] = {};
    uint64_t raysFiltered = 0;
    // The lanes whose near field the pass decides (near_field.h): Embree starts them beyond it
    // (nearTnear), decideNearField tests its triangles in double.
    uint32_t nearLanes = 0;

    // A directional light's direction is every lane's, on every tile: set here once (Embree reads
    // a ray's direction and never writes it), so that fillRays copies positional lights' alone.
    HardPacket(const Accel& accel, const HardLight& light)
        : ctx(accel.shadowContext(/*coherent=*/true)), directional(light.directional) {
        RTCRay16& ray = rayHit.ray;
        for (int k = 0; k < 16; ++k) {
            ray.tnear[k] = 0.0f;
            ray.time[k] = 0.0f;
            ray.mask[k] = 0xFFFFFFFFu;
            ray.flags[k] = 0;
            ray.dir_x[k] = -light.lsDirectionF.x;
            ray.dir_y[k] = -light.lsDirectionF.y;
            ray.dir_z[k] = -light.lsDirectionF.z;
        }
    }
    bool directional;
};
;

// The tile's valid mask from the setup: lanes outside the image (the last tile row or column)
// are padding, neither traced nor written. Returns the number of rays to trace.
// The per-lane bookkeeping of a packet in SSE2 (sse_lanes.h).
__m128i laneBytes(const ShadowRayKind* kinds) {
    static_assert(sizeof(ShadowRayKind) == 1);
    return _mm_loadu_si128(reinterpret_cast<const __m128i*>(kinds));
}
// The lanes of `kind` (a byte per lane, 0 or 1, summed: x86-64 has no popcount instruction
// before x86-64-v2, and GCC calls a library function for one).
int countLanes(__m128i bytes, ShadowRayKind kind) {
    const __m128i ones =
        _mm_and_si128(_mm_cmpeq_epi8(bytes, _mm_set1_epi8(char(kind))), _mm_set1_epi8(1));
    const __m128i sums = _mm_sad_epu8(ones, _mm_setzero_si128());  // two 64-bit halves
    return _mm_cvtsi128_si32(sums) + _mm_extract_epi16(sums, 4);
}

[[gnu::always_inline]] inline int classifyLanes(HardPacket& p, int cols, int rows) {
    alignas(16) ShadowRayKind kinds[16];
    std::memcpy(kinds, p.ps.kind, sizeof kinds);
    if (cols < SurfaceBuffer::kTile || rows < SurfaceBuffer::kTile)  // the image's edge
        for (int k = 0; k < 16; ++k)
            if ((k & 3) >= cols || (k >> 2) >= rows) kinds[k] = ShadowRayKind::Padding;
    const __m128i bytes = laneBytes(kinds);
    // valid: -1 on traced lanes, the byte compare widened to 32 bits.
    const __m128i traced = _mm_cmpeq_epi8(bytes, _mm_set1_epi8(char(ShadowRayKind::Traced)));
    const int tracedMask = _mm_movemask_epi8(traced);
    if (tracedMask == 0xFFFF) {  // most tiles: every lane traced, no other kind to count
        p.counts[int(ShadowRayKind::Traced)] += 16;
    } else {
        for (int kind = 0; kind < int(ShadowRayKind::Count); ++kind)
            p.counts[kind] += uint64_t(countLanes(bytes, ShadowRayKind(kind)));
    }
    const __m128i lo = _mm_unpacklo_epi8(traced, traced), hi = _mm_unpackhi_epi8(traced, traced);
    __m128i* valid = reinterpret_cast<__m128i*>(p.valid);
    _mm_store_si128(valid + 0, _mm_unpacklo_epi16(lo, lo));
    _mm_store_si128(valid + 1, _mm_unpackhi_epi16(lo, lo));
    _mm_store_si128(valid + 2, _mm_unpacklo_epi16(hi, hi));
    _mm_store_si128(valid + 3, _mm_unpackhi_epi16(hi, hi));
    return setBits16(uint32_t(tracedMask));
}

// Whether a traced lane leaves within its origin triangle's tangency bound (offset.h), where only
// the origin filter keeps it from hitting that triangle (a NaN cosine counts as within).
[[gnu::always_inline]] inline bool needsOriginFilter(const SurfaceBuffer& sb, size_t base,
                                                     const HardPacket& p) {
    __m128 near = _mm_setzero_ps();
    for (int g = 0; g < 16; g += 4) {
        const __m128 clear = _mm_cmpge_ps(_mm_load_ps(p.ps.cosine + g),
                                          _mm_loadu_ps(&sb.tangentCos[base + size_t(g)]));
        const __m128 valid =
            _mm_castsi128_ps(_mm_load_si128(reinterpret_cast<const __m128i*>(p.valid + g)));
        near = _mm_or_ps(near, _mm_andnot_ps(clear, valid));
    }
    return _mm_movemask_ps(near) != 0;
}

// The traced lanes' rays. `ids`: the origin triangles' ids too, which only a filter reads (the
// origin filter, or an alpha-tested mesh's): a 4-byte stream a pixel spared where none runs.
[[gnu::always_inline]] inline void fillRays(const SurfaceBuffer& sb, size_t base, bool ids,
                                            HardPacket& p) {
    RTCRay16& ray = p.rayHit.ray;
    for (int k = 0; k < 16; ++k) {
        ray.org_x[k] = sb.lsOriginX[base + size_t(k)];
        ray.org_y[k] = sb.lsOriginY[base + size_t(k)];
        ray.org_z[k] = sb.lsOriginZ[base + size_t(k)];
        ray.tfar[k] = p.ps.tfar[k];
    }
    if (ids)
        for (int k = 0; k < 16; ++k) ray.id[k] = sb.originId[base + size_t(k)];
    if (p.directional) return;
    for (int k = 0; k < 16; ++k) {
        ray.dir_x[k] = p.ps.dirX[k];
        ray.dir_y[k] = p.ps.dirY[k];
        ray.dir_z[k] = p.ps.dirZ[k];
    }
}

// V and cos of one tile, written row by row (each tile row is contiguous in the image); with
// `occDist` (the contact effect) the closest occluder's distance too. Embree sets tfar to -inf on
// a hit; lanes not traced get V = 0. Returns the occluded rays.
[[gnu::always_inline]] inline uint64_t writeTile(const HardPacket& p, const LocalFrame& frame,
                                                 size_t row0, size_t width, int cols, int rows,
                                                 const HardShadowPlanes& out) {
    const RTCRay16& ray = p.rayHit.ray;
    alignas(64) float lit[16];
    if (out.occDist) {
        for (int k = 0; k < 16; ++k)
            lit[k] = p.valid[k] && p.rayHit.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID ? 1.0f : 0.0f;
    } else {
        for (int g = 0; g < 16; g += 4) {
            const __m128 valid =
                _mm_castsi128_ps(_mm_load_si128(reinterpret_cast<const __m128i*>(p.valid + g)));
            const __m128 reached = _mm_cmpge_ps(_mm_load_ps(ray.tfar + g), _mm_setzero_ps());
            _mm_store_ps(lit + g, _mm_and_ps(_mm_and_ps(valid, reached), _mm_set1_ps(1.0f)));
        }
    }
    int occluded = 0;
    for (int g = 0; g < 16; g += 4) {
        const __m128 valid =
            _mm_castsi128_ps(_mm_load_si128(reinterpret_cast<const __m128i*>(p.valid + g)));
        const __m128 dark = _mm_cmpeq_ps(_mm_load_ps(lit + g), _mm_setzero_ps());
        occluded += setBits4(_mm_movemask_ps(_mm_and_ps(valid, dark)));
    }
    if (cols == SurfaceBuffer::kTile && rows == SurfaceBuffer::kTile) {
        for (int r = 0; r < 4; ++r) {
            _mm_storeu_ps(out.V + row0 + size_t(r) * width, _mm_load_ps(lit + 4 * r));
            _mm_storeu_ps(out.cosine + row0 + size_t(r) * width, _mm_load_ps(p.ps.cosine + 4 * r));
        }
    } else {
        for (int r = 0; r < rows; ++r)
            for (int c = 0; c < cols; ++c) {
                out.V[row0 + size_t(r) * width + size_t(c)] = lit[r * 4 + c];
                out.cosine[row0 + size_t(r) * width + size_t(c)] = p.ps.cosine[r * 4 + c];
            }
    }
    if (out.occDist)
        for (int r = 0; r < rows; ++r)
            for (int c = 0; c < cols; ++c) {
                const int k = r * 4 + c;
                out.occDist[row0 + size_t(r) * width + size_t(c)] =
                    !p.valid[k]     ? -1.0f
                    : lit[k] != 0.f ? std::numeric_limits<float>::infinity()
                                    : float(frame.wsLength(ray.tfar[k]));
            }
    return uint64_t(occluded);
}

// The open lanes' near fields: the empty ones dropped (a NaN cosine leaves a lane open whatever
// its bound), the others started beyond their ball with their triangles fetched into the cache
// meanwhile, for decideNearField after the trace. Rare (a few lanes in a thousand on the bench's
// terrain): out of line. Returns the lanes kept.
[[gnu::noinline]] uint64_t fetchNearLanes(const NearFields& f, size_t base, HardPacket& p) {
    for (int k = 0; k < 16; ++k) {
        if (!(p.nearLanes >> k & 1u)) continue;
        const size_t s = base + size_t(k);
        if (f.from(s) == f.to(s + 1)) {
            p.nearLanes &= ~(1u << k);
            continue;
        }
        p.rayHit.ray.tnear[k] = f.tnear[s];
        const char* first = reinterpret_cast<const char*>(&f.triangles[f.from(s)]);
        const size_t bytes = std::min<size_t>(f.to(s + 1) - f.from(s), 2) * sizeof(NearTriangle);
        for (size_t byte = 0; byte < bytes; byte += 64) _mm_prefetch(first + byte, _MM_HINT_T0);
    }
    return uint64_t(setBits16(p.nearLanes));
}

// The traced lanes whose near field the pass decides (near_field.h): those whose cosine does not
// rule it out at once against the slot's sine bound, both within their float errors: the cosine's
// own is far under 1e-5 (kTieCos), the direction's a few ulp (1e-5 is far above) plus, for a
// positional light, the rounding of the surface point and the light's position to float over the
// distance (the tie test's bound, 4x wider; +inf at the light itself). Lane by lane, four at a
// time, with no test of the tile first: the bounds' line is fetched with the tile's
// (prefetchTile), and a tile-wide bound would cost a load and a reduction on every tile to spare
// these few compares. Sets nearLanes; returns their number.
[[gnu::always_inline]] inline uint64_t markNearLanes(const Accel& accel, const SurfaceBuffer& sb,
                                                     const HardLight& light, size_t base,
                                                     HardPacket& p) {
    p.nearLanes = 0;
    const NearFields& f = sb.nearFields;
    if (!accel.filters() || !f.built()) return 0;
    const __m128 fixedError = _mm_set1_ps(2e-5f), tie = _mm_set1_ps(4.0f * light.lsTieScale);
    const bool directional = light.directional;
    uint32_t open = 0;
    for (int g = 0; g < 16; g += 4) {
        __m128 error = fixedError;
        if (!directional) error = _mm_add_ps(error, _mm_div_ps(tie, _mm_load_ps(p.ps.tfar + g)));
        const __m128 sine = _mm_sub_ps(_mm_load_ps(p.ps.cosine + g), error);
        // Not ruled out: NaN compares false, so it stays. An empty field's bound is -inf.
        const __m128 notOut = _mm_cmpngt_ps(sine, _mm_loadu_ps(&f.sineBound[base + size_t(g)]));
        open |= uint32_t(_mm_movemask_ps(_mm_and_ps(notOut, laneMask4(p.valid, g)))) << g;
    }
    p.nearLanes = open;
    return open ? fetchNearLanes(f, base, p) : 0;
}

// The lanes whose near field the pass decides, after Embree traced them from beyond it: all their
// near-field triangles against the true segment from the surface point, in double. A crossing
// before the lane's end (or, closest-hit, before Embree's hit) occludes it. Returns the lanes it
// changed.
uint64_t decideNearField(const SurfaceBuffer& sb, size_t base, bool closest, HardPacket& p) {
    uint64_t changed = 0;
    RTCRay16& ray = p.rayHit.ray;
    const NearFields& f = sb.nearFields;
    for (int k = 0; k < 16; ++k) {
        if (!(p.nearLanes >> k & 1u)) continue;
        const bool hit =
            closest ? p.rayHit.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID : !(ray.tfar[k] >= 0.0f);
        if (hit && !closest) continue;
        const double tEnd = hit ? double(ray.tfar[k]) : double(p.ps.tfar[k]);
        const glm::dvec3 dir(p.ps.dirX[k], p.ps.dirY[k], p.ps.dirZ[k]);
        const size_t s = base + size_t(k);
        const double t = nearFirstHit(&f.triangles[f.from(s)], f.to(s + 1) - f.from(s), dir, tEnd);
        if (!(t < tEnd)) continue;
        ++changed;
        if (closest) {
            p.rayHit.hit.geomID[k] = 0;  // any valid id: writeTile reads only whether and where
            ray.tfar[k] = float(t);
        } else {
            ray.tfar[k] = -std::numeric_limits<float>::infinity();
        }
    }
    return changed;
}

// A coming tile's lines of every per-slot array the pass reads (a tile's 16 slots are one 64-byte
// line of each), fetched while Embree traces this one: a tile touches a dozen such streams
// between two traces, more than the hardware prefetcher follows once the traversal has run.
// Two tiles ahead: the bench's profile (perf, oracle alone) had the pass's own share of the
// samples lowest there (one tile ahead: its loads still waited; four: no better).
[[gnu::always_inline]] inline void prefetchTile(const SurfaceBuffer& sb, size_t base) {
    if (base >= sb.hit.size()) return;
    const auto line = [&](const void* p) {
        _mm_prefetch(static_cast<const char*>(p), _MM_HINT_T0);
    };
    line(&sb.lsPointX[base]), line(&sb.lsPointY[base]), line(&sb.lsPointZ[base]);
    line(&sb.lsNormalX[base]), line(&sb.lsNormalY[base]), line(&sb.lsNormalZ[base]);
    line(&sb.lsOriginX[base]), line(&sb.lsOriginY[base]), line(&sb.lsOriginZ[base]);
    line(&sb.tangentCos[base]), line(&sb.hit[base]);
    const NearFields& f = sb.nearFields;
    // The near field's bounds, and where an open lane's starts and ends (fetchNearLanes): the
    // open lanes are few, but each would otherwise wait on two lines from memory.
    if (f.built()) line(&f.sineBound[base]), line(&f.tnear[base]), line(&f.begin[base]);
}

// The next tile's rows of V and cos (a line holds four tiles' rows: mostly already here), so that
// writeTile's stores find their lines.
[[gnu::always_inline]] inline void prefetchOutput(const HardShadowPlanes& out, size_t row0,
                                                  size_t width, int rows) {
    for (int r = 0; r < rows; ++r) {
        _mm_prefetch(reinterpret_cast<const char*>(out.V + row0 + size_t(r) * width), _MM_HINT_T0);
        _mm_prefetch(reinterpret_cast<const char*>(out.cosine + row0 + size_t(r) * width),
                     _MM_HINT_T0);
    }
}

// One tile: setup, trace (any hit, or the closest with the contact effect), write.
SO_HARD_CLONES void traceTile(const Accel& accel, const SurfaceBuffer& sb, const HardLight& light,
                              int tx, int ty, HardPacket& p, const HardShadowPlanes& out,
                              HardShadowStats& st) {
    const size_t base = (size_t(ty) * size_t(sb.tilesX) + size_t(tx)) * 16;
    const int x0 = tx * SurfaceBuffer::kTile, y0 = ty * SurfaceBuffer::kTile;
    const int cols = std::min(SurfaceBuffer::kTile, sb.width - x0);
    const int rows = std::min(SurfaceBuffer::kTile, sb.height - y0);
    prefetchTile(sb, base + 32);  // two tiles on
    if (tx + 1 < sb.tilesX)
        prefetchOutput(out, size_t(y0) * size_t(sb.width) + size_t(x0 + 4), size_t(sb.width), rows);
    setupPacketLanes(accel, sb, base, light, p.ps);
    const int active = classifyLanes(p, cols, rows);
    if (active) {
        const bool filter = needsOriginFilter(sb, base, p);
        fillRays(sb, base, filter || accel.alphaTested(), p);
        st.nearFieldPixels += markNearLanes(accel, sb, light, base, p);
        p.ctx.originFilter(filter);
        p.raysFiltered += filter ? uint64_t(active) : 0;
        if (out.occDist) {
            for (int k = 0; k < 16; ++k) p.rayHit.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect16(p.valid, accel.rtcScene(), &p.ctx.rtc, &p.rayHit);
            st.closestHitQueries += uint64_t(active);
        } else {
            rtcOccluded16(p.valid, accel.rtcScene(), &p.ctx.rtc, &p.rayHit.ray);
        }
        if (p.nearLanes) {
            st.nearFieldOccluded += decideNearField(sb, base, out.occDist != nullptr, p);
            for (int k = 0; k < 16;
                 ++k)  // fillRays leaves tnear: 0 but where fetchNearLanes set it
                if (p.nearLanes >> k & 1u) p.rayHit.ray.tnear[k] = 0.0f;
        }
    }
    st.raysOccluded += writeTile(p, accel.frame(), size_t(y0) * size_t(sb.width) + size_t(x0),
                                 size_t(sb.width), cols, rows, out);
}

}  // namespace

HardShadowStats traceHardShadows(const Accel& accel, const SurfaceBuffer& sb,
                                 const HardLight& light, const HardShadowPlanes& out,
                                 Progress* progress) {
    auto t0 = std::chrono::steady_clock::now();
    tbb::combinable<HardShadowStats> partial;
    // A chunk of rows: the thread's counts and the chunk's packet (which counts as it goes).
    struct Scratch {
        HardShadowStats& st;
        HardPacket packet;
    };
    const bool spot = light.spot;
    forEachTileRow(
        sb.tilesY,
        [&] {
            return Scratch{partial.local(), HardPacket(accel, light)};
        },
        [&](int ty, Scratch& c) {
            for (int tx = 0; tx < sb.tilesX; ++tx)
                traceTile(accel, sb, light, tx, ty, c.packet, out, c.st);
            if (progress) progress->advance(uint64_t(SurfaceBuffer::kTile) * uint64_t(sb.width));
        },
        [&](Scratch& c, uint64_t alphaTestsRun) {
            const auto count = [&](ShadowRayKind k) { return c.packet.counts[int(k)]; };
            HardShadowStats chunk;
            chunk.skippedBackground = count(ShadowRayKind::Background);
            chunk.skippedAttached = count(ShadowRayKind::Attached);
            // Counted only for the lights they apply to (oracle.json leaves them out elsewhere).
            if (spot) chunk.skippedOutsideCone = count(ShadowRayKind::OutsideCone);
            if (light.oneSided) chunk.skippedBehindLight = count(ShadowRayKind::BehindLight);
            chunk.raysTraced = count(ShadowRayKind::Traced);
            chunk.exactDecisions = c.packet.ps.exactDecisions;
            chunk.alphaTests = alphaTestsRun;
            chunk.raysFiltered = c.packet.raysFiltered;
            combineStats(c.st, chunk);
        });
    HardShadowStats total;
    if (spot) total.skippedOutsideCone = 0;
    if (light.oneSided) total.skippedBehindLight = 0;
    partial.combine_each([&](const HardShadowStats& s) { combineStats(total, s); });
    total.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return total;
}

}  // namespace so
