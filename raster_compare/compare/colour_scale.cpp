#include "raster_compare/compare/colour_scale.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace so {

ColourScale scaleOf(const std::vector<double>& values) {
    constexpr double kLogWhenRatioAbove = 10.0;
    ColourScale s;
    if (values.empty()) return s;
    s.lo = *std::min_element(values.begin(), values.end());
    s.hi = *std::max_element(values.begin(), values.end());
    double minPositive = 0.0;
    for (double v : values)
        if (v > 0.0 && (minPositive == 0.0 || v < minPositive)) minPositive = v;
    if (minPositive > 0.0 && s.hi / minPositive > kLogWhenRatioAbove) {
        s.log = true;
        s.lo = minPositive;  // zeros take the lowest colour
    }
    return s;
}

double scalePosition(const ColourScale& s, double v) {
    if (s.hi <= s.lo || v <= s.lo) return 0.0;
    if (v >= s.hi) return 1.0;
    return s.log ? std::log(v / s.lo) / std::log(s.hi / s.lo) : (v - s.lo) / (s.hi - s.lo);
}

Rgb rampColour(double t) {
    const double x = std::clamp(t, 0.0, 1.0) * double(kViridis.size() - 1);
    const size_t k = std::min(kViridis.size() - 2, size_t(x));
    const double f = x - double(k);
    Rgb c{};
    for (size_t i = 0; i < 3; ++i)
        c[i] = int(std::lround(kViridis[k][i] + f * (kViridis[k + 1][i] - kViridis[k][i])));
    return c;
}

std::string hexColour(const Rgb& c) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "#%02x%02x%02x", c[0], c[1], c[2]);
    return buf;
}

std::string textColour(const Rgb& c) {
    double luminance = 0.0;
    const double weights[3] = {0.2126, 0.7152, 0.0722};
    for (size_t i = 0; i < 3; ++i) {
        const double s = c[i] / 255.0;
        luminance += weights[i] * (s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4));
    }
    return 1.05 / (luminance + 0.05) > (luminance + 0.05) / 0.05 ? "#fff" : "#000";
}

std::string rampGradient() {
    std::string g = "linear-gradient(to right";
    for (const Rgb& c : kViridis) g += "," + hexColour(c);
    return g + ")";
}

}  // namespace so
