// Values to colours for the pages' matrices and heat maps (the index page, the sweep report): one
// scale rule and one ramp, so the same error has the same colour on both.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace so {

// Errors often span decades (acne from 0.3 on the plain shadow map down to 1e-4 with a bias): a
// linear scale would paint everything but the worst cell the same colour, so values whose positive
// range spans more than 10x are drawn on a log scale, a 0 taking the lowest colour.
struct ColourScale {
    double lo = 0.0, hi = 0.0;
    bool log = false;
};

ColourScale scaleOf(const std::vector<double>& values);

// 0 at the scale's lowest value, 1 at its highest.
double scalePosition(const ColourScale& s, double v);

// Viridis (matplotlib's, sampled at nine points): sequential, perceptually uniform and readable
// with any colour vision; dark purple is the lowest error, yellow the highest.
using Rgb = std::array<int, 3>;
inline constexpr std::array<Rgb, 9> kViridis = {{{68, 1, 84},
                                                 {72, 40, 120},
                                                 {62, 73, 137},
                                                 {49, 104, 142},
                                                 {38, 130, 142},
                                                 {31, 158, 137},
                                                 {53, 183, 121},
                                                 {110, 206, 88},
                                                 {253, 231, 37}}};

// The ramp at t in [0, 1], interpolated linearly between its points.
Rgb rampColour(double t);
// "#rrggbb"
std::string hexColour(const Rgb& c);
// Black or white, whichever has the higher WCAG contrast on this background, so a value stays
// legible on every step of the ramp.
std::string textColour(const Rgb& c);
// "linear-gradient(to right,#440154,...)": the ramp for a legend.
std::string rampGradient();

}  // namespace so
