#include "raster_compare/compare/metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/channels.h"
#include "core/percentile.h"
#include "raster_compare/compare/metric_table.h"

namespace so {

namespace {

namespace ch = channels;
constexpr float kInf = std::numeric_limits<float>::infinity();

// Squared Euclidean distance transform of one row or column, the lower envelope of parabolas
// (Felzenszwalb and Huttenlocher, "Distance Transforms of Sampled Functions", 2012). "No seed" is a
// large finite value rather than infinity, so that differences stay defined.
constexpr double kFar = 1e30;
void edt1d(const std::vector<double>& f, std::vector<double>& d, std::vector<int>& v,
           std::vector<double>& z) {
    const int n = int(f.size());
    int k = 0;
    v[0] = 0;
    z[0] = -1e300;
    z[1] = 1e300;
    auto cross = [&](int q, int p) {
        return ((f[size_t(q)] + double(q) * q) - (f[size_t(p)] + double(p) * p)) / (2.0 * (q - p));
    };
    for (int q = 1; q < n; ++q) {
        double s = cross(q, v[size_t(k)]);
        while (s <= z[size_t(k)]) {
            --k;
            s = cross(q, v[size_t(k)]);
        }
        ++k;
        v[size_t(k)] = q;
        z[size_t(k)] = s;
        z[size_t(k) + 1] = 1e300;
    }
    k = 0;
    for (int q = 0; q < n; ++q) {
        while (z[size_t(k) + 1] < q) ++k;
        const int p = v[size_t(k)];
        d[size_t(q)] = double(q - p) * (q - p) + f[size_t(p)];
    }
}

// Distance in pixels from every pixel to the nearest pixel of `seed` (+inf if there is none).
std::vector<float> distanceTo(const std::vector<uint8_t>& seed, int w, int h) {
    std::vector<double> g(seed.size());
    for (size_t i = 0; i < seed.size(); ++i) g[i] = seed[i] ? 0.0 : kFar;
    const size_t n = size_t(std::max(w, h));
    std::vector<double> f, d;
    std::vector<double> z(n + 1);
    std::vector<int> v(n);
    for (int x = 0; x < w; ++x) {
        f.resize(size_t(h));
        d.resize(size_t(h));
        for (int y = 0; y < h; ++y) f[size_t(y)] = g[size_t(y) * size_t(w) + size_t(x)];
        edt1d(f, d, v, z);
        for (int y = 0; y < h; ++y) g[size_t(y) * size_t(w) + size_t(x)] = d[size_t(y)];
    }
    std::vector<float> out(seed.size());
    for (int y = 0; y < h; ++y) {
        f.assign(g.begin() + long(size_t(y) * size_t(w)),
                 g.begin() + long(size_t(y + 1) * size_t(w)));
        d.resize(size_t(w));
        edt1d(f, d, v, z);
        for (int x = 0; x < w; ++x)
            out[size_t(y) * size_t(w) + size_t(x)] =
                d[size_t(x)] >= 0.5 * kFar ? kInf : float(std::sqrt(d[size_t(x)]));
    }
    return out;
}

// Shadow boundary pixels: lit (V > 0.5) hit pixels with a shadowed hit 4-neighbour. Marking only
// the lit side makes a shadow shifted by k pixels measure exactly k.
std::vector<uint8_t> boundaries(const float* A, const float* V, int w, int h) {
    std::vector<uint8_t> b(size_t(w) * size_t(h), 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            if (A[i] == 0.0f || !(V[i] > 0.5f)) continue;
            const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
            for (int k = 0; k < 4; ++k) {
                if (nx[k] < 0 || ny[k] < 0 || nx[k] >= w || ny[k] >= h) continue;
                const size_t j = size_t(ny[k]) * size_t(w) + size_t(nx[k]);
                if (A[j] != 0.0f && !(V[j] > 0.5f)) b[i] = 1;
            }
        }
    return b;
}

// The channels of one light in both images.
struct Planes {
    Planes(const ChannelImage& oracle, const ChannelImage& raster, const std::string& light)
        : w(oracle.width()), h(oracle.height()), n(oracle.pixelCount()) {
        Ao = oracle.channel(ch::kHit);
        Ar = raster.channel(ch::kHit);
        Vo = oracle.channel(ch::lightChannel(light, ch::kVisibility));
        Vr = raster.channel(ch::lightChannel(light, ch::kVisibility));
        Co = oracle.channel(ch::lightChannel(light, ch::kCosine));
        mo = oracle.channel(ch::kMeshId), po = oracle.channel(ch::kPrimId);
        mr = raster.channel(ch::kMeshId), pr = raster.channel(ch::kPrimId);
        const std::string seName = ch::lightChannel(light, ch::kStdErr),
                          occName = ch::lightChannel(light, ch::kOccluderDistance);
        SE = oracle.has(seName) ? oracle.channel(seName) : nullptr;
        D = oracle.has(occName) ? oracle.channel(occName) : nullptr;
        area = SE != nullptr;
        const bool normals = oracle.has(ch::kNX) && oracle.has(ch::kNY) && oracle.has(ch::kNZ);
        No[0] = normals ? oracle.channel(ch::kNX) : nullptr;
        No[1] = normals ? oracle.channel(ch::kNY) : nullptr;
        No[2] = normals ? oracle.channel(ch::kNZ) : nullptr;
        const auto optional = [&](const char* suffix) {
            const std::string name = ch::lightChannel(light, suffix);
            return raster.has(name) ? raster.channel(name) : nullptr;
        };
        MD = optional(ch::kMapDepth), RD = optional(ch::kReceiverDepth);
        MT = optional(ch::kMapTexel), VU = optional(ch::kVisibilityUnfiltered);
        depthCause = MD && RD && MT;
        if (!depthCause) VU = nullptr;
    }
    int w, h;
    size_t n;
    const float *Ao, *Ar, *Vo, *Vr, *Co, *mo, *po, *mr, *pr;
    const float* SE;     // the oracle's standard error: sampled area lights only
    const float* D;      // the oracle's occluder distance: the contact effect only
    const float* No[3];  // the oracle's normals, where its image has them (null otherwise)
    // What the raster's own depth comparison saw (shadow-map techniques with a depth map; null
    // for the others and for external images): the map's depth at the receiver's texel, the
    // receiver's depth, the map texel's size (world units), and where a screen-space pass
    // filtered V afterwards (blur), the comparison's own V.
    const float *MD, *RD, *MT, *VU;
    bool depthCause;  // MD, RD and MT: acne is classed by its cause
    bool area;
};

// Whether the map, at the receiver's own texel, holds the receiver's own surface: its depth within
// texel (1 + tan theta) of the receiver's (docs/metrics.md, the self-shadow margin). The texel's
// centre, where the map sampled the surface, lies within sqrt(2)/2 texel of the receiver's point
// across the map, where a plane at angle theta to the light is up to sqrt(2)/2 tan theta texels
// deeper or shallower; the rest is room for the depth buffer's rounding and the surface's
// curvature within a texel. A separate occluder lies further in front: its shadow is not acne.
bool ownSurfaceInMap(const Planes& p, size_t i) {
    const double texel = p.MT[i], cosTheta = p.Co[i];
    // Nothing compared (texel 0), or the receiver beyond the map (+inf: nothing can shadow it).
    if (!(texel > 0.0) || !std::isfinite(p.MD[i]) || !(cosTheta > 0.0)) return false;
    const double tanTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta)) / cosTheta;
    return std::fabs(double(p.RD[i]) - double(p.MD[i])) <= texel * (1.0 + tanTheta);
}

// Which pixels count (docs/metrics.md): both see the same triangle, lit side of the light.
std::vector<uint8_t> countedPixels(const Planes& p, LightMetrics& m) {
    std::vector<uint8_t> counted(p.n, 0);
    for (size_t i = 0; i < p.n; ++i) {
        if (p.Ao[i] == 0.0f || p.Ar[i] == 0.0f) {
            ++m.excludedBackground;
        } else if (p.mo[i] != p.mr[i] || p.po[i] != p.pr[i]) {
            ++m.excludedDifferentSurface;
        } else if (!(p.Co[i] > 0.0f)) {
            ++m.excludedFacingAway;
        } else {
            counted[i] = 1;
            ++m.counted;
        }
    }
    return counted;
}

// How one counted pixel is wrong (docs/metrics.md): on an area light a difference within the
// oracle's own 95% interval is not an error (its half-width is 0 where the oracle states stderr 0);
// on a hard light the pixel is wrong only when the difference passes 0.5.
struct PixelError {
    double hw, err;
    bool falseShadow, falseLit;
};

PixelError pixelError(const Planes& p, size_t i) {
    const double o = p.Vo[i], r = p.Vr[i];
    const double hw = p.area ? ch::kStdErrQuantile95 * p.SE[i] : 0.0;
    return {hw, std::max(0.0, std::fabs(r - o) - hw), p.area ? r < o - hw : r < o - 0.5,
            p.area ? r > o + hw : r > o + 0.5};
}

// Two neighbouring pixels on one surface: the same mesh, and (where the oracle has normals) no
// crease between them. A technique's penumbra spreads over the surface that receives the true
// one; across an edge it would join a surface's own acne to a shadow on its neighbour (the
// soft_chair's back, acned all over, stands on the seat's penumbra). 30 degrees is far more than
// a curved mesh turns from one pixel to the next.
constexpr float kCreaseCos = 0.866f;  // cos 30 degrees
bool sameSurface(const Planes& p, size_t a, size_t b) {
    if (p.mo[a] != p.mo[b]) return false;
    if (!p.No[0]) return true;
    float dot = 0.0f;
    for (const float* N : p.No) dot += N[a] * N[b];
    return dot >= kCreaseCos;
}

// Where the oracle's penumbra lies, the seeds of the spread: counted pixels with 0 < O < 1 (part
// of the light blocked, not all of it), and where the true penumbra is narrower than a pixel, both
// pixels of a step from O = 0 to O = 1 on one surface.
std::vector<uint8_t> penumbraSeeds(const Planes& p, const std::vector<uint8_t>& counted) {
    std::vector<uint8_t> seed(p.n, 0);
    for (int y = 0; y < p.h; ++y)
        for (int x = 0; x < p.w; ++x) {
            const size_t i = size_t(y) * size_t(p.w) + size_t(x);
            const float o = p.Vo[i];
            if (!counted[i]) continue;
            if (o > 0.0f && o < 1.0f) seed[i] = 1;
            if (o != 0.0f && o != 1.0f) continue;
            const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
            for (int k = 0; k < 4; ++k) {
                if (nx[k] < 0 || ny[k] < 0 || nx[k] >= p.w || ny[k] >= p.h) continue;
                const size_t j = size_t(ny[k]) * size_t(p.w) + size_t(nx[k]);
                if (counted[j] && p.Vo[j] == 1.0f - o && sameSurface(p, i, j)) seed[i] = 1;
            }
        }
    return seed;
}

// Which side of the oracle's penumbra a pixel is wrong on within the technique's own penumbra
// (0 < R < 1): false shadow where the oracle says fully lit, false lit where it says umbra.
enum SpreadSide : uint8_t { kNoSide, kLitSide, kUmbraSide };
SpreadSide spreadSide(const Planes& p, size_t i) {
    if (!(p.Vr[i] > 0.0f && p.Vr[i] < 1.0f)) return kNoSide;
    const PixelError e = pixelError(p, i);
    if (p.Vo[i] == 1.0f && e.falseShadow) return kLitSide;
    if (p.Vo[i] == 0.0f && e.falseLit) return kUmbraSide;
    return kNoSide;
}

// Penumbra spread (area lights; docs/metrics.md): a wrong pixel outside the oracle's penumbra,
// soft in the technique's, joined to the oracle's penumbra by a chain of such pixels (8-connected,
// one side of it, one surface). An over-wide or shifted penumbra is such a chain; a surface's own
// speckles lie apart from it. A flood fill from the seeds: each pixel enters the queue once, and
// what it reaches does not depend on the order, so the result is the same on every run.
std::vector<uint8_t> penumbraSpread(const Planes& p, const std::vector<uint8_t>& counted) {
    std::vector<uint8_t> spread(p.n, 0);
    if (!p.area) return spread;
    std::vector<uint8_t> side(p.n, kNoSide);
    for (size_t i = 0; i < p.n; ++i)
        if (counted[i]) side[i] = spreadSide(p, i);
    const std::vector<uint8_t> seed = penumbraSeeds(p, counted);
    std::vector<size_t> queue;
    for (size_t i = 0; i < p.n; ++i)
        if (seed[i]) {
            queue.push_back(i);
            spread[i] = side[i] != kNoSide;  // a wrong pixel of a penumbra narrower than a pixel
        }
    for (size_t head = 0; head < queue.size(); ++head) {
        const size_t j = queue[head];
        const int x = int(j % size_t(p.w)), y = int(j / size_t(p.w));
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int nx = x + dx, ny = y + dy;
                if (nx < 0 || ny < 0 || nx >= p.w || ny >= p.h) continue;
                const size_t k = size_t(ny) * size_t(p.w) + size_t(nx);
                if (seed[k] || spread[k] || side[k] == kNoSide) continue;
                // Beyond the seeds a chain keeps to its side: lit-side and umbra-side pixels meet
                // only across the penumbra.
                if ((!seed[j] && side[j] != side[k]) || !sameSurface(p, j, k)) continue;
                spread[k] = 1;
                queue.push_back(k);
            }
    }
    return spread;
}

// Sums and counts over the counted pixels, for the rates.
struct Tally {
    double sumAbs = 0, sumSq = 0;
    size_t falseShadow = 0, falseLit = 0;
    size_t acneEligible = 0, acne = 0, aliasEligible = 0, aliased = 0, ppEligible = 0, pp = 0,
           umbra = 0, bleed = 0, pen = 0, spread = 0, screenBleed = 0;
    double leak = 0.0, penAbs = 0.0, penSoft = 0.0;
    size_t umbraExact = 0, litExact = 0;
    double umbraAbs = 0.0, litAbs = 0.0;
    size_t band = 0, otherShadow = 0, otherLit = 0;
    double bandAbs = 0.0;
    size_t ghostEligible = 0, ghost = 0;
};

// The class a wrong pixel is drawn as (1 + its Artifact; 0: not a wrong pixel): the first, in
// order of precedence, that explains it, or "other" when none does (marked in `is` and counted).
size_t drawnClass(bool fs, bool fl, std::array<bool, kArtifactCount>& is, Tally& t) {
    if (!fs && !fl) return 0;
    for (const ArtifactClass& c : kArtifactClasses)
        if (is[size_t(c.id)]) return 1 + size_t(c.id);
    const Artifact other = fs ? Artifact::OtherFalseShadow : Artifact::OtherFalseLit;
    ++(fs ? t.otherShadow : t.otherLit);
    is[size_t(other)] = true;
    return 1 + size_t(other);
}

// The classes of a wrong pixel that no edge explains (docs/metrics.md), into `is` and the tally:
// ghosting (false shadow or false lit where the truth has just changed), acne (false shadow on
// fully lit pixels away from the oracle's boundary) and screen-space bleed.
void ownShadowClasses(const Planes& p, size_t i, bool awayFromBoundary, bool spread,
                      const MetricOptions& options, Tally& t,
                      std::array<bool, kArtifactCount>& is) {
    const PixelError e = pixelError(p, i);
    const bool fs = e.falseShadow, fl = e.falseLit, fullyLit = p.Vo[i] == 1.0f;
    auto set = [&](Artifact a, bool v) { is[size_t(a)] = v; };
    // In a sequence, where the truth has just changed: away from the oracle's boundary and outside
    // its penumbra (where an edge's own error is aliasing or penumbra whatever came before), a
    // wrong pixel shows a truth that is gone: ghosting (docs/metrics.md#sequence).
    const bool inPenumbra = p.area && p.Vo[i] > 0.0f && p.Vo[i] < 1.0f;
    bool ghost = false;
    if (options.truthChanged && (*options.truthChanged)[i] && awayFromBoundary && !inPenumbra) {
        ++t.ghostEligible;
        ghost = fs || fl;
        t.ghost += ghost;
        set(Artifact::Ghosting, ghost);
    }
    // Where the raster says what its own depth comparison saw: a false shadow that its comparison
    // gave (the map at its texel holding its own surface) is acne; one its comparison did not
    // give, but a screen-space pass carried over from a neighbour, is screen-space bleed. The pass
    // must have darkened the pixel: a filtered map's own partial V (pcf's kernel) above 0.5, which
    // no pass touched, is judged as it is without V_unfiltered (contact=on keeps acne as off).
    const bool ownLit = p.VU && p.VU[i] > 0.5f && p.Vr[i] < p.VU[i];
    if (fullyLit && awayFromBoundary) {
        ++t.acneEligible;
        // A penumbra reaching too far, or an old shadow kept, is not a surface shadowing itself;
        // nor can a technique that compares no depth shadow a surface by its own.
        const bool acne = fs && !spread && !ghost && options.comparesDepth &&
                          (!p.depthCause || (!ownLit && ownSurfaceInMap(p, i)));
        t.acne += acne;
        set(Artifact::Acne, acne);
    }
    if (fullyLit && fs && !spread && ownLit) {
        ++t.screenBleed;
        set(Artifact::ScreenBleed, true);
    }
}

// One counted pixel into the tally and the error maps. Each class marks where the pixel counts
// as that class's error (the classes may overlap); a wrong pixel (false shadow or false lit) is
// also drawn as exactly one class (drawnClass). `spread`: penumbraSpread's verdict on the pixel.
void classify(const Planes& p, size_t i, float toOracleBoundary, bool spread,
              const MetricOptions& options, LightMetrics& m, Tally& t, ErrorMaps* maps) {
    const double o = p.Vo[i], r = p.Vr[i];
    const auto [hw, err, fs, fl] = pixelError(p, i);
    t.sumAbs += err;
    t.sumSq += err * err;
    m.maxAbs = std::max(m.maxAbs, err);
    t.falseShadow += fs;
    t.falseLit += fl;
    const bool inUmbra = p.area ? o <= hw : o == 0.0;
    std::array<bool, kArtifactCount> is{};
    auto set = [&](Artifact a, bool v) { is[size_t(a)] = v; };
    const bool awayFromBoundary = toOracleBoundary > float(options.boundaryRadius);
    ownShadowClasses(p, i, awayFromBoundary, spread, options, t, is);
    if (!awayFromBoundary) {
        ++t.band;
        t.bandAbs += err;
        if (!p.area) {
            ++t.aliasEligible;
            t.aliased += fs || fl;
            set(Artifact::Aliasing, fs || fl);
        }
    }
    if (p.D && inUmbra && p.D[i] >= 0.0f && p.D[i] < options.contactThreshold) {
        ++t.ppEligible;
        if (fl) {
            ++t.pp;
            t.leak = std::max(t.leak, double(p.D[i]));
            set(Artifact::PeterPanning, true);
        }
    }
    if (inUmbra) {
        ++t.umbra;
        t.bleed += r > o + 0.1;
        set(Artifact::LightBleeding, options.filteredTechnique && r > o + 0.1);
    }
    t.spread += spread;
    set(Artifact::PenumbraSpread, spread);
    if (p.area && o > 0.0 && o < 1.0) {
        ++t.pen;
        t.penAbs += err;
        set(Artifact::Penumbra, err > 0.0);
        t.penSoft += (r - o) * (o < 0.5 ? 1.0 : -1.0);  // > 0: nearer 0.5 than the truth
    }
    if (p.area && o == 0.0) {
        ++t.umbraExact;
        t.umbraAbs += err;
    }
    if (p.area && o == 1.0) {
        ++t.litExact;
        t.litAbs += err;
    }
    const size_t shown = drawnClass(fs, fl, is, t);
    if (!maps) return;
    maps->error[i] = float(err);
    for (size_t k = 0; k < kArtifactCount; ++k)
        if (is[k]) maps->classes[k][i] = 1.0f;
    maps->shown[i] = uint8_t(shown);
}

void setRates(const Tally& t, const Planes& p, const MetricOptions& options, LightMetrics& m) {
    const auto share = [](size_t a, size_t b) { return b ? double(a) / double(b) : 0.0; };
    m.mae = m.counted ? t.sumAbs / double(m.counted) : 0.0;
    m.rmse = m.counted ? std::sqrt(t.sumSq / double(m.counted)) : 0.0;
    m.falseShadowRate = share(t.falseShadow, m.counted);
    m.falseLitRate = share(t.falseLit, m.counted);
    m.acneRate = share(t.acne, t.acneEligible);
    if (!p.area) m.aliasingRate = share(t.aliased, t.aliasEligible);
    if (t.band) m.boundaryBandMae = t.bandAbs / double(t.band);
    m.otherFalseShadowRate = share(t.otherShadow, m.counted);
    m.otherFalseLitRate = share(t.otherLit, m.counted);
    m.ghostingEligible = t.ghostEligible;
    m.ghostingPixels = t.ghost;
    if (p.D) {
        m.peterPanningRate = share(t.pp, t.ppEligible);
        m.lightLeakDistance = t.leak;
    }
    if (options.filteredTechnique) m.lightBleedingRate = share(t.bleed, t.umbra);
    if (p.VU) m.screenBleedRate = share(t.screenBleed, m.counted);
    if (p.area) {
        m.penumbraSpreadRate = share(t.spread, m.counted);
        m.penumbraMae = t.pen ? t.penAbs / double(t.pen) : 0.0;
        m.penumbraBias = t.pen ? t.penSoft / double(t.pen) : 0.0;
        m.umbraMae = t.umbraExact ? t.umbraAbs / double(t.umbraExact) : 0.0;
        m.litMae = t.litExact ? t.litAbs / double(t.litExact) : 0.0;
    }
}

// Both ways: each raster boundary pixel to the nearest oracle one and each oracle boundary pixel
// to the nearest raster one.
// When one image has no boundary at all, the other's boundary pixels are the image diagonal away:
// a shadow dropped (or invented) entirely is the worst result, never the best.
BoundaryDisplacement boundaryDisplacement(const std::vector<uint8_t>& bo,
                                          const std::vector<uint8_t>& br,
                                          const std::vector<float>& toOracleBoundary,
                                          const std::vector<float>& toRasterBoundary,
                                          double diagonal) {
    std::vector<double> dist;
    for (size_t i = 0; i < bo.size(); ++i) {
        if (br[i])
            dist.push_back(std::isfinite(toOracleBoundary[i]) ? toOracleBoundary[i] : diagonal);
        if (bo[i])
            dist.push_back(std::isfinite(toRasterBoundary[i]) ? toRasterBoundary[i] : diagonal);
    }
    BoundaryDisplacement b;
    const bool oracleHas = std::find(bo.begin(), bo.end(), 1) != bo.end(),
               rasterHas = std::find(br.begin(), br.end(), 1) != br.end();
    b.missingBoundary = oracleHas != rasterHas;
    b.pixels = dist.size();
    if (!dist.empty()) {
        double s = 0.0;
        for (double d : dist) s += d;
        b.mean = s / double(dist.size());
        b.p95 = nearestRankPercentile(dist, 0.95);
        b.max = *std::max_element(dist.begin(), dist.end());
    }
    return b;
}

// With the raster's NAME.aliasing_pred: its mean over counted pixels, and where the prediction
// says texels are large, whether raster shadow edges stray further (Pearson correlation).
void predictedAliasing(const ChannelImage& raster, const std::string& light,
                       const std::vector<uint8_t>& counted, const std::vector<uint8_t>& br,
                       const std::vector<float>& toOracleBoundary, LightMetrics& m) {
    const std::string apName = ch::lightChannel(light, ch::kPredictedAliasing);
    if (!raster.has(apName)) return;
    const float* AP = raster.channel(apName);
    const size_t n = counted.size();
    double sum = 0.0;
    for (size_t i = 0; i < n; ++i)
        if (counted[i]) sum += AP[i];
    m.predictedAliasingMean = m.counted ? sum / double(m.counted) : 0.0;
    double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    size_t k = 0;
    for (size_t i = 0; i < n; ++i) {
        if (!br[i] || !std::isfinite(toOracleBoundary[i]) || !(AP[i] > 0.0f)) continue;
        const double x = std::log(double(AP[i])), y = toOracleBoundary[i];
        sx += x, sy += y, sxx += x * x, syy += y * y, sxy += x * y;
        ++k;
    }
    const double cov = sxy - sx * sy / double(std::max<size_t>(k, 1));
    const double vx = sxx - sx * sx / double(std::max<size_t>(k, 1)),
                 vy = syy - sy * sy / double(std::max<size_t>(k, 1));
    if (k >= 10 && vx > 0.0 && vy > 0.0) m.aliasingCorrelation = cov / std::sqrt(vx * vy);
}

}  // namespace

LightMetrics computeLightMetrics(const ChannelImage& oracle, const ChannelImage& raster,
                                 const std::string& light, const MetricOptions& options,
                                 ErrorMaps* maps) {
    const Planes p(oracle, raster, light);
    if (options.truthChanged && options.truthChanged->size() != p.n)
        throw std::invalid_argument("computeLightMetrics: truthChanged has " +
                                    std::to_string(options.truthChanged->size()) +
                                    " pixels, the images " + std::to_string(p.n));
    if (maps) {
        for (std::vector<float>& v : maps->classes) v.assign(p.n, 0.0f);
        maps->error.assign(p.n, 0.0f);
        maps->shown.assign(p.n, 0);
    }
    LightMetrics m;
    const std::vector<uint8_t> counted = countedPixels(p, m);
    if (maps) maps->counted = counted;
    const std::vector<uint8_t> bo = boundaries(p.Ao, p.Vo, p.w, p.h),
                               br = boundaries(p.Ar, p.Vr, p.w, p.h);
    const std::vector<float> toOracleBoundary = distanceTo(bo, p.w, p.h),
                             toRasterBoundary = distanceTo(br, p.w, p.h);
    const std::vector<uint8_t> spread = penumbraSpread(p, counted);
    Tally t;
    for (size_t i = 0; i < p.n; ++i)
        if (counted[i]) classify(p, i, toOracleBoundary[i], spread[i] != 0, options, m, t, maps);
    setRates(t, p, options, m);
    m.boundaryDisplacement = boundaryDisplacement(bo, br, toOracleBoundary, toRasterBoundary,
                                                  std::hypot(double(p.w), double(p.h)));
    predictedAliasing(raster, light, counted, br, toOracleBoundary, m);
    if (p.area) m.penumbraWidth = penumbraWidthError(p.w, p.h, p.Vo, p.Vr, counted);
    return m;
}

bool familyComparesDepth(const std::string& family) {
    static const std::array<const char*, 3> kNoDepthComparison = {"ray tracing", "shadow texture",
                                                                  "planar projection"};
    return std::none_of(kNoDepthComparison.begin(), kNoDepthComparison.end(),
                        [&](const char* f) { return family == f; });
}

namespace {
void flatten(const nlohmann::json& j, const std::string& prefix,
             std::vector<std::pair<std::string, nlohmann::json>>& out) {
    for (auto it = j.begin(); it != j.end(); ++it) {
        const std::string name = prefix.empty() ? it.key() : prefix + "." + it.key();
        if (it->is_object())
            flatten(*it, name, out);
        else if (!it->is_array())  // a series (sequence.mae_per_frame) is no one metric
            out.emplace_back(name, *it);
    }
}
}  // namespace

std::vector<std::pair<std::string, nlohmann::json>> flatMetrics(const nlohmann::json& row) {
    std::vector<std::pair<std::string, nlohmann::json>> out;
    flatten(row, "", out);
    return out;
}

// Every cost of the metric table at its name after "cost." (a work count inside "work", which is
// one null where the counts are unknown: an image's).
nlohmann::json TechniqueCost::toJson() const {
    nlohmann::json j = nlohmann::json::object();
    if (!work) j["work"] = nullptr;
    const std::string prefix = "cost.", workPrefix = "work.";
    for (const MetricInfo& m : allMetrics()) {
        if (!m.cost) continue;
        const std::string name = std::string(m.name).substr(prefix.size());
        if (name.rfind(workPrefix, 0) != 0)
            j[name] = m.cost(*this);
        else if (work)
            j["work"][name.substr(workPrefix.size())] = m.cost(*this);
    }
    return j;
}

nlohmann::json LightComparison::toJson() const {
    nlohmann::json j = metrics.toJson();
    if (temporal) temporal->addToJson(j);
    if (sequence) j["sequence"] = sequence->toJson();
    j["cost"] = cost.toJson();
    return j;
}

nlohmann::json LightMetrics::toJson() const {
    auto opt = [](const std::optional<double>& v) {
        return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
    };
    const double total =
        double(counted + excludedBackground + excludedDifferentSurface + excludedFacingAway);
    return {{"counted_pixels", counted},
            {"excluded_share",
             {{"background", total > 0 ? excludedBackground / total : 0.0},
              {"different_surface", total > 0 ? excludedDifferentSurface / total : 0.0},
              {"facing_away", total > 0 ? excludedFacingAway / total : 0.0}}},
            {"mae", mae},
            {"rmse", rmse},
            {"max_abs", maxAbs},
            {"false_shadow_rate", falseShadowRate},
            {"false_lit_rate", falseLitRate},
            {artifactClass(Artifact::Acne).metric, acneRate},
            {artifactClass(Artifact::ScreenBleed).metric, opt(screenBleedRate)},
            {artifactClass(Artifact::PenumbraSpread).metric, opt(penumbraSpreadRate)},
            {artifactClass(Artifact::PeterPanning).metric, opt(peterPanningRate)},
            {"light_leak_distance", opt(lightLeakDistance)},
            {"boundary_displacement_px",
             {{"mean", boundaryDisplacement.mean},
              {"p95", boundaryDisplacement.p95},
              {"max", boundaryDisplacement.max},
              {"missing_boundary", boundaryDisplacement.missingBoundary}}},
            {"boundary_band_mae", opt(boundaryBandMae)},
            {artifactClass(Artifact::Aliasing).metric, opt(aliasingRate)},
            {artifactClass(Artifact::OtherFalseShadow).metric, otherFalseShadowRate},
            {artifactClass(Artifact::OtherFalseLit).metric, otherFalseLitRate},
            {artifactClass(Artifact::LightBleeding).metric, opt(lightBleedingRate)},
            {artifactClass(Artifact::Penumbra).metric, opt(penumbraMae)},
            {"penumbra_bias", opt(penumbraBias)},
            {"umbra_mae", opt(umbraMae)},
            {"lit_mae", opt(litMae)},
            {"penumbra_width_error_px",
             penumbraWidth ? nlohmann::json{{"mean", penumbraWidth->mean},
                                            {"p95", penumbraWidth->p95},
                                            {"oracle_mean_width", penumbraWidth->oracleMeanWidth},
                                            {"profiles", penumbraWidth->profiles}}
                           : nlohmann::json(nullptr)},
            {"predicted_aliasing",
             {{"mean", opt(predictedAliasingMean)},
              {"correlation_with_boundary_error", opt(aliasingCorrelation)}}}};
}

}  // namespace so
