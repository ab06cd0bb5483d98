#include "raster_compare/compare/penumbra_width.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/percentile.h"

namespace so {

namespace {

constexpr double kStep = 0.25, kReach = 128.0;

struct Line {
    double x, y, dx, dy;  // centre (pixel units, pixel centres at +0.5) and unit direction
};

// The oracle's gradient at pixel (x, y) by central differences over counted neighbours.
bool gradientAt(int w, int h, const float* V, const std::vector<uint8_t>& counted, int x, int y,
                double& gx, double& gy) {
    auto at = [&](int xx, int yy, double fallback) {
        if (xx < 0 || yy < 0 || xx >= w || yy >= h) return fallback;
        const size_t j = size_t(yy) * size_t(w) + size_t(xx);
        return counted[j] ? double(V[j]) : fallback;
    };
    const double c = V[size_t(y) * size_t(w) + size_t(x)];
    gx = 0.5 * (at(x + 1, y, c) - at(x - 1, y, c));
    gy = 0.5 * (at(x, y + 1, c) - at(x, y - 1, c));
    return std::hypot(gx, gy) > 1e-6;
}

// Samples along one half of the line (sign +1: towards the lit side, -1: the other), adding the
// length where each profile is inside (0.1, 0.9). False when the line leaves the counted pixels
// before both profiles are past their transition (towards >= 0.9 or <= 0.1).
bool march(int w, int h, const float* Vo, const float* Vr, const std::vector<uint8_t>& counted,
           const Line& l, int sign, double& widthO, double& widthR) {
    for (double t = kStep; t <= kReach; t += kStep) {
        const int x = int(std::floor(l.x + sign * t * l.dx)),
                  y = int(std::floor(l.y + sign * t * l.dy));
        if (x < 0 || y < 0 || x >= w || y >= h) return false;
        const size_t j = size_t(y) * size_t(w) + size_t(x);
        if (!counted[j]) return false;
        const double o = Vo[j], r = Vr[j];
        widthO += (o > 0.1 && o < 0.9) ? kStep : 0.0;
        widthR += (r > 0.1 && r < 0.9) ? kStep : 0.0;
        const bool past = sign > 0 ? (o >= 0.9 && r >= 0.9) : (o <= 0.1 && r <= 0.1);
        if (past) return true;
    }
    return false;
}

}  // namespace

std::optional<PenumbraWidthError> penumbraWidthError(int w, int h, const float* Vo, const float* Vr,
                                                     const std::vector<uint8_t>& counted) {
    std::vector<double> errors;
    double oracleSum = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            if (!counted[i]) continue;
            bool crosses = false;
            for (int d = 0; d < 2 && !crosses; ++d) {
                const int xn = x + (d == 0), yn = y + (d == 1);
                if (xn >= w || yn >= h) continue;
                const size_t j = size_t(yn) * size_t(w) + size_t(xn);
                crosses = counted[j] && (Vo[i] - 0.5f) * (Vo[j] - 0.5f) < 0.0f;
            }
            double gx = 0.0, gy = 0.0;
            if (!crosses || !gradientAt(w, h, Vo, counted, x, y, gx, gy)) continue;
            const double len = std::hypot(gx, gy);
            const Line l{x + 0.5, y + 0.5, gx / len, gy / len};
            const double o0 = Vo[i], r0 = Vr[i];
            double widthO = (o0 > 0.1 && o0 < 0.9) ? kStep : 0.0;
            double widthR = (r0 > 0.1 && r0 < 0.9) ? kStep : 0.0;
            if (!march(w, h, Vo, Vr, counted, l, +1, widthO, widthR) ||
                !march(w, h, Vo, Vr, counted, l, -1, widthO, widthR))
                continue;
            errors.push_back(std::fabs(widthR - widthO));
            oracleSum += widthO;
        }
    if (errors.empty()) return std::nullopt;
    PenumbraWidthError e;
    e.profiles = errors.size();
    double sum = 0.0;
    for (double v : errors) sum += v;
    e.mean = sum / double(errors.size());
    e.oracleMeanWidth = oracleSum / double(errors.size());
    e.p95 = nearestRankPercentile(std::move(errors), 0.95);
    return e;
}

}  // namespace so
