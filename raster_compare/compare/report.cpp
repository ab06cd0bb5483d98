#include "raster_compare/compare/report.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>

#include "core/channels.h"
#include "core/error.h"
#include "core/preview.h"
#include "raster_compare/compare/tradeoff.h"

namespace so {

namespace {

namespace ch = channels;

std::string html(const std::string& s) {
    std::string o;
    for (char c : s)
        o += c == '<'   ? "&lt;"
             : c == '>' ? "&gt;"
             : c == '&' ? "&amp;"
             : c == '"' ? "&quot;"
                        : std::string(1, c);
    return o;
}

std::string imgTag(int w, int h, const std::vector<float>& rgb, const std::string& alt) {
    return "<img alt=\"" + html(alt) + "\" src=\"data:image/png;base64," +
           base64(encodePngRgb(w, h, rgb)) + "\">";
}

// The oracle's cosine times a visibility, so a person sees the shadows.
std::vector<float> shaded(const ChannelImage& oracle, const float* V, const std::string& light) {
    return shadowGrey(oracle, V, oracle.channel(ch::lightChannel(light, ch::kCosine)));
}

// Every wrong pixel in the colour of the one class it is shown as (ErrorMaps::shown), over the
// dimmed truth: the coloured pixels are exactly the false-shadow and false-lit ones.
std::vector<float> errorMap(const ChannelImage& oracle, const ErrorMaps& m,
                            const std::string& light) {
    const float* V = oracle.channel(ch::lightChannel(light, ch::kVisibility));
    const float* A = oracle.channel(ch::kHit);
    std::vector<float> rgb(oracle.pixelCount() * 3);
    for (size_t i = 0; i < oracle.pixelCount(); ++i) {
        const float grey = A[i] == 0.0f ? 0.03f : 0.12f + 0.18f * V[i];
        const float* c = m.shown[i] ? kArtifactClasses[m.shown[i] - 1].rgb : nullptr;
        for (int k = 0; k < 3; ++k) rgb[3 * i + size_t(k)] = c ? c[k] : grey;
    }
    return rgb;
}

// The magnitude scale of the area-light error maps: black (0) through blue and orange to pale
// yellow at kMagnitudeMax and above (a sequential ramp readable with any colour vision).
constexpr float kMagnitudeMax = 0.5f;
std::array<float, 3> magnitudeColour(float e) {
    constexpr float stops[5][3] = {{0.05f, 0.05f, 0.08f},
                                   {0.0f, 0.45f, 0.70f},
                                   {0.80f, 0.47f, 0.65f},
                                   {0.90f, 0.62f, 0.0f},
                                   {0.98f, 0.95f, 0.70f}};
    const float t = std::clamp(e / kMagnitudeMax, 0.0f, 1.0f) * 4.0f;
    const int k = std::min(3, int(t));
    const float f = t - float(k);
    return {stops[k][0] + f * (stops[k + 1][0] - stops[k][0]),
            stops[k][1] + f * (stops[k + 1][1] - stops[k][1]),
            stops[k][2] + f * (stops[k + 1][2] - stops[k][2])};
}

// Area lights: |V_raster - V_oracle| beyond the oracle's interval, per pixel, on that scale.
std::vector<float> magnitudeMap(const ChannelImage& oracle, const ErrorMaps& m) {
    const float* A = oracle.channel(ch::kHit);
    std::vector<float> rgb(oracle.pixelCount() * 3, 0.03f);
    for (size_t i = 0; i < oracle.pixelCount(); ++i) {
        if (A[i] == 0.0f) continue;
        const std::array<float, 3> c = magnitudeColour(m.error[i]);
        std::copy(c.begin(), c.end(), rgb.begin() + long(3 * i));
    }
    return rgb;
}

// The numbered bar beside the magnitude maps.
std::string magnitudeBar() {
    std::ostringstream s;
    s << "<svg class=\"bar\" viewBox=\"0 0 260 34\" width=\"260\" height=\"34\" role=\"img\" "
         "aria-label=\"error magnitude scale\"><defs><linearGradient id=\"mag\">";
    for (int k = 0; k <= 8; ++k) {
        const std::array<float, 3> c = magnitudeColour(kMagnitudeMax * float(k) / 8.0f);
        s << "<stop offset=\"" << k * 12.5 << "%\" stop-color=\"rgb(" << int(c[0] * 255) << ","
          << int(c[1] * 255) << "," << int(c[2] * 255) << ")\"/>";
    }
    s << "</linearGradient></defs><rect x=\"10\" y=\"2\" width=\"240\" height=\"12\" "
         "fill=\"url(#mag)\"/>";
    for (int k = 0; k <= 4; ++k)
        s << "<text x=\"" << 10 + 60 * k << "\" y=\"30\" class=\"tick\" text-anchor=\"middle\">"
          << kMagnitudeMax * float(k) / 4.0f << (k == 4 ? "+" : "") << "</text>";
    s << "</svg>";
    return s.str();
}

// Predicted aliasing on a log ramp: blue where a texel is smaller than a pixel, white at 1, red
// where it covers several pixels (saturating at 1/8 and 8).
std::vector<float> aliasingMap(const ChannelImage& raster, const std::string& light) {
    const float* AP = raster.channel(ch::lightChannel(light, ch::kPredictedAliasing));
    std::vector<float> rgb(raster.pixelCount() * 3, 0.05f);
    for (size_t i = 0; i < raster.pixelCount(); ++i) {
        if (!(AP[i] > 0.0f)) continue;
        const float t = std::clamp(std::log2(AP[i]) / 3.0f, -1.0f, 1.0f);
        rgb[3 * i] = t > 0 ? 1.0f : 1.0f + t;
        rgb[3 * i + 1] = 1.0f - std::fabs(t);
        rgb[3 * i + 2] = t < 0 ? 1.0f : 1.0f - t;
    }
    return rgb;
}

std::string num(std::optional<double> v, int digits = 4) {
    if (!v) return "–";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*g", digits, *v);
    return buf;
}

// One light's techniques as points of error against cost (docs/metrics.md, "Error against
// cost"): penumbra_mae on area lights (the oracle's curve beside them), mae on hard ones.
struct ChartData {
    std::vector<TradeoffPoint> points;
    std::vector<std::pair<double, double>> oracle;  // (ms, penumbra mean stated half-width)
    std::string error;                              // the error's name, for the axis
};

ChartData chartData(const ReportInput& in, size_t light) {
    ChartData d;
    const bool area = std::any_of(
        in.techniques.begin(), in.techniques.end(),
        [&](const ReportTechnique& t) { return t.lights[light].metrics.penumbraMae.has_value(); });
    d.error = area ? "penumbra_mae" : "mae";
    for (const ReportTechnique& t : in.techniques) {
        const LightMetrics& m = t.lights[light].metrics;
        if (area && !m.penumbraMae) continue;
        d.points.push_back({t.label, t.curve, t.quality, t.lights[light].cost.frameMs.median,
                            area ? *m.penumbraMae : m.mae});
    }
    if (area && light < in.oracleCurves.size())
        for (const auto& [ms, e] : in.oracleCurves[light])
            if (ms > 0.0 && e > 0.0) d.oracle.emplace_back(ms, e);
    return d;
}

// Log-log axes over every point and the oracle's curve, ticks and names drawn.
struct ChartAxes {
    double tMin = 1e300, tMax = 0.0, eMin = 1e300, eMax = 0.0;
    static constexpr double W = 600, H = 340, L = 80, B = 40, R = 20, T = 20;
    explicit ChartAxes(const ChartData& d) {
        auto extend = [&](double t, double e) {
            tMin = std::min(tMin, t), tMax = std::max(tMax, t), eMax = std::max(eMax, e);
            if (e > 0.0) eMin = std::min(eMin, e);
        };
        for (const TradeoffPoint& p : d.points) extend(p.ms, p.error);
        for (const auto& [t, e] : d.oracle) extend(t, e);
        tMin = std::max(tMin, 1e-3) / 1.3;
        tMax = std::max(tMax * 1.3, tMin * 10);
        eMin = eMin == 1e300 ? 1e-6 : eMin / 2;  // zero errors drawn at the floor
        eMax = std::max(eMax * 1.5, eMin * 10);
    }
    double x(double t) const {
        return L + (W - L - R) * std::log(std::max(t, tMin) / tMin) / std::log(tMax / tMin);
    }
    double y(double e) const {
        return H - B - (H - B - T) * std::log(std::max(e, eMin) / eMin) / std::log(eMax / eMin);
    }
    // A point's label above it, to its right, or to its left near the right edge.
    void label(std::ostream& s, double t, double e, const std::string& text) const {
        const bool left = x(t) > W - R - 7.0 * double(text.size());
        s << "<text x=\"" << x(t) + (left ? -7 : 7) << "\" y=\"" << y(e) - 6 << "\" class=\"label\""
          << (left ? " text-anchor=\"end\"" : "") << ">" << html(text) << "</text>";
    }
    void draw(std::ostream& s, const std::string& error) const {
        s << "<line x1=\"" << L << "\" y1=\"" << H - B << "\" x2=\"" << W - R << "\" y2=\"" << H - B
          << "\" class=\"axis\"/><line x1=\"" << L << "\" y1=\"" << T << "\" x2=\"" << L
          << "\" y2=\"" << H - B << "\" class=\"axis\"/>";
        for (int k = 0; k <= 4; ++k) {
            const double tk = tMin * std::pow(tMax / tMin, k / 4.0),
                         ek = eMin * std::pow(eMax / eMin, k / 4.0);
            s << "<text x=\"" << x(tk) << "\" y=\"" << H - B + 16
              << "\" class=\"tick\" text-anchor=\"middle\">" << num(tk, 3) << "</text>";
            s << "<text x=\"" << L - 6 << "\" y=\"" << y(ek) + 4
              << "\" class=\"tick\" text-anchor=\"end\">" << num(ek, 2) << "</text>";
        }
        s << "<text x=\"" << (L + W - R) / 2 << "\" y=\"" << H - 6
          << "\" text-anchor=\"middle\">frame time (ms, log scale)</text><text x=\"14\" y=\""
          << (T + H - B) / 2 << "\" transform=\"rotate(-90 14 " << (T + H - B) / 2
          << ")\" text-anchor=\"middle\">" << html(error) << " (log scale)</text>";
    }
};

// The curves over each technique's quality parameter: a line through its settings, each point
// labelled with the parameter's value, the curve with the technique's name at its last point.
void drawCurves(std::ostream& s, const ChartData& d, const ChartAxes& ax) {
    for (const TradeoffCurve& c : qualityCurves(d.points)) {
        s << "<polyline class=\"curve\" points=\"";
        for (size_t i : c.points)
            s << ax.x(d.points[i].ms) << "," << ax.y(d.points[i].error) << " ";
        s << "\"><title>" << html(c.key) << "</title></polyline>";
        for (size_t i : c.points)
            s << "<text x=\"" << ax.x(d.points[i].ms) + 6 << "\" y=\""
              << ax.y(d.points[i].error) + 14 << "\" class=\"tick\">" << num(d.points[i].quality, 4)
              << "</text>";
        const TradeoffPoint& last = d.points[c.points.back()];
        ax.label(s, last.ms, last.error, c.key.substr(0, c.key.find(' ')));
    }
}

// Error against cost: every setting a point, the curves over quality parameters, the Pareto
// front, and on area lights the oracle's own curve.
std::string chart(const ChartData& d) {
    if (d.points.empty()) return "";
    const ChartAxes ax(d);
    std::ostringstream s;
    s << "<svg class=\"chart\" viewBox=\"0 0 " << ax.W << " " << ax.H << "\" width=\"" << ax.W
      << "\" height=\"" << ax.H << "\" role=\"img\" aria-label=\"error against time\">";
    ax.draw(s, d.error);
    if (!d.oracle.empty()) {
        s << "<polyline class=\"oracle\" points=\"";
        for (const auto& [t, e] : d.oracle) s << ax.x(t) << "," << ax.y(e) << " ";
        s << "\"><title>the oracle: mean stated 95% half-width over the penumbra against its "
             "time</title></polyline><text x=\""
          << ax.x(d.oracle.back().first) - 4 << "\" y=\"" << ax.y(d.oracle.back().second) - 8
          << "\" class=\"label\" text-anchor=\"end\">oracle (its 95% half-width)</text>";
    }
    const std::vector<size_t> front = paretoFront(d.points);
    s << "<polyline class=\"pareto\" points=\"";
    for (size_t i : front) s << ax.x(d.points[i].ms) << "," << ax.y(d.points[i].error) << " ";
    s << "\"/>";
    drawCurves(s, d, ax);
    std::vector<uint8_t> onCurve(d.points.size(), 0);
    for (const TradeoffCurve& c : qualityCurves(d.points))
        for (size_t i : c.points) onCurve[i] = 1;
    for (size_t i = 0; i < d.points.size(); ++i) {
        const TradeoffPoint& p = d.points[i];
        const bool onFront = std::find(front.begin(), front.end(), i) != front.end();
        s << "<circle cx=\"" << ax.x(p.ms) << "\" cy=\"" << ax.y(p.error) << "\" r=\"5\" class=\""
          << (onFront ? "front" : "point") << "\"><title>" << html(p.label) << ": " << num(p.error)
          << " at " << num(p.ms, 3) << " ms</title></circle>";
        if (!onCurve[i]) ax.label(s, p.ms, p.error, p.label);
    }
    s << "</svg>";
    return s.str();
}

// The chart read off at error budgets: the cheapest setting within each, and (area lights) the
// oracle's time to state intervals that small.
std::string budgetTable(const ChartData& d) {
    if (d.points.empty()) return "";
    std::ostringstream s;
    s << "<p>The red dashed line is the Pareto front: the settings no other setting beats in both "
         "time and "
      << html(d.error) << ". Lines join the settings of one technique that differ only in its "
      << "quality parameter (numbers: its value).</p><table class=\"budget\"><tr><th>"
      << html(d.error) << " at most</th><th>cheapest setting</th><th>its frame ms</th>"
      << (d.oracle.empty() ? "" : "<th>oracle ms to state 95% intervals that small</th>")
      << "</tr>";
    for (double budget : {0.2, 0.1, 0.05, 0.02, 0.01, 0.005}) {
        const std::optional<size_t> best = cheapestWithin(d.points, budget);
        s << "<tr><td>" << num(budget, 3) << "</td><td>"
          << (best ? html(d.points[*best].label) : "none") << "</td><td>"
          << (best ? num(d.points[*best].ms, 3) : "–") << "</td>";
        if (!d.oracle.empty()) {
            const std::optional<double> ms = oracleMsAtError(d.oracle, budget);
            s << "<td>" << (ms ? num(*ms, 3) : "not within its run") << "</td>";
        }
        s << "</tr>";
    }
    s << "</table>";
    return s.str();
}

// The metrics table: a header and how to read the value from a row (none: the label columns).
struct Column {
    std::string header;
    std::function<std::optional<double>(const LightComparison&)> value;
};

const std::vector<Column>& columns() {
    using L = const LightComparison&;
    auto artifact = [](Artifact a) { return std::string(artifactClass(a).legend); };
    static const std::vector<Column> cols = {
        {"technique", nullptr},
        {"family", nullptr},
        {"light", nullptr},
        {"mae", [](L l) { return std::optional(l.metrics.mae); }},
        {"rmse", [](L l) { return std::optional(l.metrics.rmse); }},
        {"false shadow", [](L l) { return std::optional(l.metrics.falseShadowRate); }},
        {"false lit", [](L l) { return std::optional(l.metrics.falseLitRate); }},
        {artifact(Artifact::Acne), [](L l) { return std::optional(l.metrics.acneRate); }},
        {artifact(Artifact::PeterPanning), [](L l) { return l.metrics.peterPanningRate; }},
        {"leak dist.", [](L l) { return l.metrics.lightLeakDistance; }},
        {"boundary p95 px", [](L l) { return std::optional(l.metrics.boundaryDisplacement.p95); }},
        {artifact(Artifact::Aliasing), [](L l) { return l.metrics.aliasingRate; }},
        {"band mae", [](L l) { return l.metrics.boundaryBandMae; }},
        {artifact(Artifact::LightBleeding), [](L l) { return l.metrics.lightBleedingRate; }},
        {artifact(Artifact::Penumbra) + " mae", [](L l) { return l.metrics.penumbraMae; }},
        {artifact(Artifact::Penumbra) + " bias", [](L l) { return l.metrics.penumbraBias; }},
        {"penumbra width err px",
         [](L l) {
             return l.metrics.penumbraWidth ? std::optional(l.metrics.penumbraWidth->mean)
                                            : std::nullopt;
         }},
        {"umbra mae", [](L l) { return l.metrics.umbraMae; }},
        {"lit mae", [](L l) { return l.metrics.litMae; }},
        {artifact(Artifact::OtherFalseShadow),
         [](L l) { return std::optional(l.metrics.otherFalseShadowRate); }},
        {artifact(Artifact::OtherFalseLit),
         [](L l) { return std::optional(l.metrics.otherFalseLitRate); }},
        {"frame ms", [](L l) { return std::optional(l.cost.frameMs.median); }},
        {"shadow pass ms", [](L l) { return std::optional(l.cost.shadowMapMs.median); }},
    };
    return cols;
}

// The page's head, title and the artifact legend.
void writeHead(std::ostream& o, const ReportInput& in) {
    o << R"(<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>shadow-oracle report: )"
      << html(in.sceneFile) << R"(</title><style>
body{font-family:system-ui,sans-serif;margin:24px;background:#f6f6f4;color:#222}
h1{font-size:22px}h2{font-size:18px;margin-top:32px}
.grid{display:flex;flex-wrap:wrap;gap:14px}.card{background:#fff;padding:8px;border-radius:6px;box-shadow:0 1px 3px #0002}
.card img{display:block;max-width:320px;image-rendering:pixelated}.card p{margin:4px 0 0;font-size:13px}
.legend span{display:inline-block;margin-right:14px;font-size:13px}.legend i{display:inline-block;width:12px;height:12px;margin-right:4px;vertical-align:-1px}
table{border-collapse:collapse;background:#fff;font-size:13px}th,td{padding:4px 8px;border-bottom:1px solid #ddd;text-align:right}
th{cursor:pointer;background:#eee;position:sticky;top:0}td:first-child,td:nth-child(2),th:first-child,th:nth-child(2){text-align:left}
.chart{background:#fff;border-radius:6px}.axis{stroke:#444}.tick{font-size:11px;fill:#555}.label{font-size:11px;fill:#333}
.point{fill:#888}.front{fill:#d33}.curve{fill:none;stroke:#999;stroke-width:1.2}.oracle{fill:none;stroke:#0072b2;stroke-width:1.5}.pareto{fill:none;stroke:#d33;stroke-width:1.5;stroke-dasharray:4 3}
footer{margin-top:32px;font-size:12px;color:#666}
</style></head><body>)";
    o << "<h1>Shadow accuracy against the oracle: " << html(in.sceneFile) << "</h1>";
    o << "<div class=\"legend\">Error map classes: ";
    for (const ArtifactClass& c : kArtifactClasses)
        o << "<span><i style=\"background:rgb(" << int(c.rgb[0] * 255) << "," << int(c.rgb[1] * 255)
          << "," << int(c.rgb[2] * 255) << ")\"></i>" << c.legend << "</span>";
    o << "<span>(grey: correct, the truth dimmed; every false-shadow or false-lit pixel has one "
         "colour)</span></div>";
}

// Pixels where the oracle spent its budget without reaching its target: their intervals are wider
// than asked, and the report says where they are.
void writeUnconverged(std::ostream& o, const ReportInput& in, const std::string& light) {
    const std::string name = ch::lightChannel(light, ch::kUnconverged);
    if (!in.oracle.has(name)) return;
    const float* U = in.oracle.channel(name);
    const float* A = in.oracle.channel(ch::kHit);
    size_t count = 0;
    std::vector<float> rgb(in.oracle.pixelCount() * 3);
    for (size_t i = 0; i < in.oracle.pixelCount(); ++i) {
        count += U[i] > 0.0f;
        const float g = A[i] == 0.0f ? 0.03f : 0.2f;
        rgb[3 * i] = U[i] > 0.0f ? 0.90f : g;
        rgb[3 * i + 1] = U[i] > 0.0f ? 0.62f : g;
        rgb[3 * i + 2] = U[i] > 0.0f ? 0.0f : g;
    }
    if (!count) return;
    o << "<div class=\"card\">"
      << imgTag(in.oracle.width(), in.oracle.height(), rgb, "oracle pixels short of the target")
      << "<p>" << count
      << " oracle pixels spent their sample budget before reaching the target error (orange): "
         "their intervals are wider</p></div>";
}

// The techniques grouped by family, families in the order they first appear, techniques in the
// order given within each.
std::vector<const ReportTechnique*> byFamily(const ReportInput& in) {
    std::vector<const ReportTechnique*> ordered;
    for (const ReportTechnique& first : in.techniques) {
        bool seen = false;
        for (const ReportTechnique* t : ordered) seen |= t->family == first.family;
        if (seen) continue;
        for (const ReportTechnique& t : in.techniques)
            if (t.family == first.family) ordered.push_back(&t);
    }
    return ordered;
}

// One light: the oracle, each technique by family, its error map and predicted aliasing, and the
// chart.
void writeLight(std::ostream& o, const ReportInput& in, size_t li) {
    const int w = in.oracle.width(), h = in.oracle.height();
    const std::string& light = in.lights[li];
    o << "<h2>Light " << html(light) << "</h2><div class=\"grid\">";
    o << "<div class=\"card\">"
      << imgTag(
             w, h,
             shaded(in.oracle, in.oracle.channel(ch::lightChannel(light, ch::kVisibility)), light),
             "oracle")
      << "<p><b>oracle</b> (ground truth)</p></div>";
    writeUnconverged(o, in, light);
    o << "</div>";
    const std::vector<const ReportTechnique*> ordered = byFamily(in);
    if (ordered.empty()) o << "<div>";  // closed below, as a family's grid would be
    for (size_t k = 0; k < ordered.size(); ++k) {
        const ReportTechnique& t = *ordered[k];
        if (k == 0 || t.family != ordered[k - 1]->family)
            o << (k == 0 ? "" : "</div>") << "<h3>" << html(t.family.empty() ? "other" : t.family)
              << "</h3><div class=\"grid\">";
        o << "<div class=\"card\">"
          << imgTag(w, h,
                    shaded(in.oracle, t.image.channel(ch::lightChannel(light, ch::kVisibility)),
                           light),
                    t.label)
          << "<p><b>" << html(t.label) << "</b></p></div>";
        o << "<div class=\"card\">"
          << imgTag(w, h, errorMap(in.oracle, t.lights[li].maps, light), t.label + " errors")
          << "<p>errors of " << html(t.label) << ": mae " << num(t.lights[li].metrics.mae)
          << "</p></div>";
        if (t.lights[li].metrics.penumbraMae) {
            o << "<div class=\"card\">"
              << imgTag(w, h, magnitudeMap(in.oracle, t.lights[li].maps), t.label + " magnitude")
              << "<p>|V - V<sub>oracle</sub>| beyond the oracle's 95% interval</p>"
              << magnitudeBar() << "</div>";
        }
        if (t.image.has(ch::lightChannel(light, ch::kPredictedAliasing))) {
            const LightMetrics& lm = t.lights[li].metrics;
            o << "<div class=\"card\">"
              << imgTag(w, h, aliasingMap(t.image, light), t.label + " predicted aliasing")
              << "<p>predicted aliasing (texel / pixel footprint; blue &lt; 1 &lt; red): mean "
              << num(lm.predictedAliasingMean, 3) << ", correlation with boundary error "
              << num(lm.aliasingCorrelation, 2) << "</p></div>";
        }
    }
    const ChartData data = chartData(in, li);
    o << "</div><h3>Error against time</h3>" << chart(data) << budgetTable(data);
}

// Every row of metrics, sortable.
void writeTable(std::ostream& o, const ReportInput& in) {
    o << "<h2>All metrics</h2><p>Click a column to sort. Times were measured on <b>"
      << html(in.timedOn) << "</b>";
    if (in.timedOn.find("llvmpipe") != std::string::npos)
        o << " (Mesa's CPU rasterizer: its times rank the techniques on this machine, not on a "
             "GPU)";
    o << "; medians over the timed frames, the techniques taking turns frame by frame. "
         "<i>noisy</i>: a spread (p25 to p75) above 20% of the median.</p>";
    o << "<table id=\"metrics\"><thead><tr>";
    for (const Column& c : columns()) o << "<th>" << c.header << "</th>";
    o << "<th>timing</th></tr></thead><tbody>";
    for (const ReportTechnique* tp : byFamily(in))
        for (size_t li = 0; li < in.lights.size(); ++li) {
            const ReportTechnique& t = *tp;
            o << "<tr><td>" << html(t.label) << "</td><td>" << html(t.family) << "</td><td>"
              << html(in.lights[li]) << "</td>";
            for (const Column& c : columns()) {
                if (!c.value) continue;
                const std::optional<double> v = c.value(t.lights[li]);
                o << "<td data-v=\"" << (v ? std::to_string(*v) : "") << "\">" << num(v) << "</td>";
            }
            o << "<td>" << (t.lights[li].cost.noisy() ? "<i>noisy</i>" : "") << "</td></tr>";
        }
    o << "</tbody></table>";
}

}  // namespace

void writeReport(const std::string& path, const ReportInput& in) {
    std::ostringstream o;
    writeHead(o, in);
    for (size_t li = 0; li < in.lights.size(); ++li) writeLight(o, in, li);
    writeTable(o, in);
    o << R"(<script>
document.querySelectorAll('#metrics th').forEach((th, col) => th.addEventListener('click', () => {
  const body = th.closest('table').tBodies[0], rows = [...body.rows];
  const dir = th.dataset.dir = th.dataset.dir === 'asc' ? 'desc' : 'asc';
  const key = r => { const c = r.cells[col]; return c.dataset.v !== undefined && c.dataset.v !== '' ? parseFloat(c.dataset.v) : c.textContent; };
  rows.sort((a, b) => { const x = key(a), y = key(b); const s = x < y ? -1 : x > y ? 1 : 0; return dir === 'asc' ? s : -s; });
  rows.forEach(r => body.appendChild(r));
}));
</script>)";
    o << "<footer>" << html(in.provenance.dump()) << "</footer></body></html>\n";
    std::ofstream f(path);
    if (!f) throwInputError(path, "", "cannot be written");
    f << o.str();
}

}  // namespace so
