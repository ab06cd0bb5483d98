// Compare's report (report.h): the page, each light's section, its images, flicker strip and
// sequence chart; the tables and the chart of error against cost are report_tables.cpp.
#include "raster_compare/compare/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "core/channels.h"
#include "core/error.h"
#include "raster_compare/compare/artifacts.h"
#include "raster_compare/compare/html.h"
#include "raster_compare/compare/metric_table.h"
#include "raster_compare/compare/report_assets.h"
#include "raster_compare/compare/report_images.h"
#include "raster_compare/compare/report_sections.h"

namespace so {

namespace report_parts {

std::string html(const std::string& s) {
    return htmlEscape(s);
}

std::string num(std::optional<double> v, int digits) {
    if (!v) return "–";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*g", digits, *v);
    return buf;
}

// The techniques grouped by family, families in the order they first appear, techniques in the
// order given within each.
std::vector<const ReportTechnique*> byFamily(const ReportInput& in) {
    std::vector<const ReportTechnique*> ordered;
    for (const ReportTechnique& first : in.techniques) {
        bool seen = false;
        for (const ReportTechnique* t : ordered) seen |= t->row.family == first.row.family;
        if (seen) continue;
        for (const ReportTechnique& t : in.techniques)
            if (t.row.family == first.row.family) ordered.push_back(&t);
    }
    return ordered;
}

std::string lightId(const ReportInput& in, size_t li) {
    return "light-" + in.lights[li];
}
std::string rowId(size_t li, size_t k) {
    return "row-" + std::to_string(li) + "-" + std::to_string(k);
}

const LightRow& lightRow(const ReportTechnique& t, const ReportInput& in, size_t li) {
    const LightRow* row = t.row.light(in.lights[li]);
    SO_CHECK(row != nullptr);  // metrics.json has every light of the scene in every row
    return *row;
}

}  // namespace report_parts

namespace {

namespace ch = channels;
using namespace report_parts;

// The classes' colours, beside the error maps; ghosting only where a sequence can have it.
std::string classLegend(bool sequence) {
    std::ostringstream o;
    o << "<div class=\"legend\">";
    for (const ArtifactClass& c : kArtifactClasses)
        if (sequence || c.id != Artifact::Ghosting)
            o << "<span><i style=\"background:rgb(" << int(c.rgb[0] * 255) << ","
              << int(c.rgb[1] * 255) << "," << int(c.rgb[2] * 255) << ")\"></i>" << c.legend
              << "</span>";
    o << "<span>grey: right (the truth, dimmed)</span></div>";
    return o.str();
}

std::string zoomable(const std::string& src, const std::string& alt, const std::string& id,
                     const std::string& oracleId) {
    return "<img class=\"zoomable\" src=\"" + src + "\" alt=\"" + html(alt) + "\"" +
           (id.empty() ? "" : " id=\"" + id + "\"") + " data-oracle=\"" + oracleId +
           "\" loading=\"lazy\">";
}

// The oracle's row: its render, the predicted aliasing (once: the first technique's that has
// it) and the pixels it left short of its target.
void writeOracleRow(std::ostream& o, const ReportInput& in, size_t li, ImageSink& sink,
                    const std::string& oracleId, const Rgb& oracleRender) {
    const int w = in.oracle.width(), h = in.oracle.height();
    const std::string& light = in.lights[li];
    const std::string l = std::to_string(li);
    o << "<tr><td><b>oracle</b><br><span class=\"muted\">the ground truth (<a "
         "href=\"oracle.exr\">oracle.exr</a>)</span></td><td>"
      << zoomable(sink.src("l" + l + "_oracle", w, h, oracleRender), "oracle", oracleId, oracleId)
      << "</td><td>";
    for (const ReportTechnique& t : in.techniques) {
        if (!t.image.has(ch::lightChannel(light, ch::kPredictedAliasing))) continue;
        o << zoomable(sink.src("l" + l + "_aliasing", w, h, aliasingMap(t.image, light)),
                      "predicted aliasing of " + t.row.label, "", oracleId)
          << "<span class=\"muted\">predicted aliasing of " << html(t.row.label)
          << ": texel over pixel footprint, blue &lt; 1 (white) &lt; red</span>";
        break;
    }
    o << "</td><td colspan=\"2\">";
    size_t count = 0;
    const Rgb unconverged = unconvergedMap(in.oracle, light, count);
    if (count)
        o << zoomable(sink.src("l" + l + "_unconverged", w, h, unconverged),
                      "oracle pixels short of the target", "", oracleId)
          << "<span class=\"muted\">" << count
          << " oracle pixels spent their sample budget before reaching the target (orange): "
             "their intervals are wider</span>";
    o << "</td></tr>";
}

// One technique's row: its render, its error map by class (and on area lights by magnitude), the
// worst square of its error map next to the oracle's, and its files.
void writeTechniqueRow(std::ostream& o, const ReportInput& in, size_t li, size_t k, ImageSink& sink,
                       const std::string& oracleId, const Rgb& oracleRender) {
    const ReportTechnique& t = in.techniques[k];
    const LightComparison& lc = t.lights[li];
    const LightRow& row = lightRow(t, in, li);
    const std::optional<double> frameMs = row.value("cost.frame_ms");
    const int w = in.oracle.width(), h = in.oracle.height();
    const std::string& light = in.lights[li];
    const std::string key = "l" + std::to_string(li) + "_" + t.fileLabel;
    const Rgb render =
        shadedImage(in.oracle, t.image.channel(ch::lightChannel(light, ch::kVisibility)), light);
    o << "<tr id=\"" << rowId(li, k) << "\"><td><b>" << html(t.row.label) << "</b>"
      << fidelityMark(t.row.fidelity, t.row.provenanceText) << historyMark(t.row.historyFrames)
      << "<br><span class=\"muted\">" << html(t.row.family) << "<br>" << html(t.parameters)
      << "<br>mae " << num(row.value("mae")) << ", frame "
      << (frameMs ? withUnit(metricInfo("cost.frame_ms"), *frameMs) : "unknown") << "<br><a href=\""
      << html(t.fileLabel) << "/raster.exr\">raster.exr</a> · <a href=\"" << html(t.fileLabel)
      << "/raster.json\">raster.json</a> · <a href=\"error_" << html(t.fileLabel)
      << ".exr\">errors</a></span></td><td>"
      << zoomable(sink.src(key + "_render", w, h, render), t.row.label, "", oracleId) << "</td><td>"
      << zoomable(sink.src(key + "_classes", w, h, classMap(in.oracle, lc.maps, light)),
                  t.row.label + " errors by class", "", oracleId)
      << "</td><td>";
    if (row.value("penumbra_mae"))
        o << zoomable(sink.src(key + "_magnitude", w, h, magnitudeMap(in.oracle, lc.maps)),
                      t.row.label + " error magnitude", "", oracleId);
    const Crop crop = worstRegion(lc.maps.error, w, h, std::max(16, std::min(w, h) / 6));
    o << "</td><td>"
      << "<img class=\"crop\" src=\""
      << sink.src(key + "_worst", crop.size, crop.size, cropOf(render, w, crop)) << "\" alt=\""
      << html(t.row.label) << " worst region\"><img class=\"crop\" src=\""
      << sink.src(key + "_worst_oracle", crop.size, crop.size, cropOf(oracleRender, w, crop))
      << "\" alt=\"oracle, same region\"><br><span class=\"muted\">at (" << crop.x << ", " << crop.y
      << "): technique, oracle</span></td></tr>";
}

void writeImages(std::ostream& o, const ReportInput& in, size_t li, ImageSink& sink) {
    const bool area = hasPenumbra(in, li);
    o << "<h3>Images</h3><p class=\"muted\">Click an image for a 1:1, 2x or 4x view; F flips it "
         "with the oracle's at the same place.</p>";
    if (area) o << oracleCertaintyNote(in.oracle, in.lights[li]);
    const std::string oracleId = "oracle-" + std::to_string(li);
    o << "<table class=\"images\"><thead><tr><th class=\"text\">technique</th><th "
         "class=\"text\">render</th><th class=\"text\">errors by class"
      << classLegend(in.sequenceFrames > 0) << "</th><th class=\"text\">"
      << (area ? "error beyond the oracle's interval" + magnitudeBar() : std::string())
      << "</th><th class=\"text\">worst region</th></tr></thead><tbody>";
    const std::string& light = in.lights[li];
    const Rgb oracleRender =
        shadedImage(in.oracle, in.oracle.channel(ch::lightChannel(light, ch::kVisibility)), light);
    writeOracleRow(o, in, li, sink, oracleId, oracleRender);
    for (const ReportTechnique* t : byFamily(in))
        writeTechniqueRow(o, in, li, size_t(t - in.techniques.data()), sink, oracleId,
                          oracleRender);
    o << "</tbody></table>";
}

// compare --frames-path: the worst technique's worst pair of frames, the flickering pixels red.
void writeFlickerStrip(std::ostream& o, const ReportInput& in, size_t li, ImageSink& sink) {
    if (in.pathFrames == 0 || li >= in.flickerStrips.size()) return;
    o << "<h3>Temporal flicker</h3>";
    const std::optional<FlickerStrip>& s = in.flickerStrips[li];
    if (!s || s->flickering == 0) {
        o << "<p class=\"muted\">No technique flickers along the camera path (" << in.pathFrames
          << " frames).</p>";
        return;
    }
    const std::string key = "flicker_" + std::to_string(li);
    const auto img = [&](const std::string& k, const Rgb& rgb, const std::string& caption) {
        o << "<figure><img src=\"" << sink.src(key + k, s->width, s->height, rgb) << "\" alt=\""
          << html(caption) << "\"><figcaption class=\"muted\">" << html(caption)
          << "</figcaption></figure>";
    };
    o << "<p>The highest temporal_flicker_rate along the camera path (" << in.pathFrames
      << " frames): <b>" << html(s->technique) << "</b>, "
      << formatMetricValue(*findMetric("temporal_flicker_rate"), s->rate) << ". Its worst pair, "
      << "frames " << s->pair << " and " << s->pair + 1 << ", has " << s->flickering
      << " flickering pixels (red; dimmed: not tracked).</p><div class=\"flicker-strip\" "
         "id=\"flicker-strip-"
      << li << "\">";
    img("_prev", visibilityGrey(s->vPrev), "frame " + std::to_string(s->pair) + ": V");
    img("_next", visibilityGrey(s->vNext), "frame " + std::to_string(s->pair + 1) + ": V");
    img("_marked", flickerMap(s->vNext, s->mask),
        "frame " + std::to_string(s->pair + 1) + ": flickering pixels");
    img("_oracle", visibilityGrey(s->vOracleNext),
        "frame " + std::to_string(s->pair + 1) + ": the oracle's V");
    o << "</div>";
}

// compare --sequence: every technique's mae at each frame of the sequence, one line each, drawn
// as SVG on the server (no script): frames along x, mae from 0 up along y.
void writeSequenceChart(std::ostream& o, const ReportInput& in, size_t li) {
    if (in.sequenceFrames == 0) return;
    static const char* kColours[] = {"#0072b2", "#d55e00", "#009e73", "#cc79a7",
                                     "#e69f00", "#56b4e9", "#000000", "#999999"};
    constexpr double kW = 640, kH = 260, kLeft = 68, kRight = 16, kTop = 12, kBottom = 36;
    const int frames = in.sequenceFrames;
    double top = 0.0;
    for (const ReportTechnique& t : in.techniques)
        if (const auto& s = t.lights[li].sequence)
            for (double e : s->maePerFrame) top = std::max(top, e);
    top = top > 0.0 ? top * 1.1 : 1.0;
    const auto x = [&](int f) {
        return kLeft + (kW - kLeft - kRight) * (frames > 1 ? double(f) / (frames - 1) : 0.5);
    };
    const auto y = [&](double e) { return kH - kBottom - (kH - kTop - kBottom) * e / top; };
    o << "<h3>Error per frame</h3><div class=\"sequence-box\" id=\"sequence-" << li
      << "\"><svg class=\"chart\" viewBox=\"0 0 " << kW << " " << kH << "\" width=\"" << kW
      << "\" height=\"" << kH << "\" role=\"img\" aria-label=\"mae per frame\">";
    for (int k = 0; k <= 4; ++k) {
        const double e = top * k / 4.0;
        o << "<line class=\"grid\" x1=\"" << kLeft << "\" x2=\"" << kW - kRight << "\" y1=\""
          << y(e) << "\" y2=\"" << y(e) << "\"/><text x=\"" << kLeft - 4 << "\" y=\"" << y(e) + 4
          << "\" text-anchor=\"end\">" << num(e, 3) << "</text>";
    }
    for (int f = 0; f < frames; f += std::max(1, frames / 8))
        o << "<text x=\"" << x(f) << "\" y=\"" << kH - kBottom + 14 << "\" text-anchor=\"middle\">"
          << f << "</text>";
    o << "<line class=\"axis\" x1=\"" << kLeft << "\" x2=\"" << kW - kRight << "\" y1=\"" << y(0)
      << "\" y2=\"" << y(0) << "\"/><text class=\"label\" x=\"" << (kLeft + kW - kRight) / 2
      << "\" y=\"" << kH - 4
      << "\" text-anchor=\"middle\">frame</text><text class=\"label\" "
      // Upright beside the tick labels, so that it never overlaps the top one.
      << "transform=\"rotate(-90)\" x=\"" << -(kTop + kH - kBottom) / 2
      << "\" y=\"12\" text-anchor=\"middle\">mae</text>";
    std::ostringstream legend;
    size_t colour = 0;
    for (const ReportTechnique* t : byFamily(in)) {
        const auto& s = t->lights[li].sequence;
        if (!s) continue;
        const char* c = kColours[colour++ % std::size(kColours)];
        o << "<polyline class=\"series\" stroke=\"" << c << "\" points=\"";
        for (size_t f = 0; f < s->maePerFrame.size(); ++f)
            o << (f ? " " : "") << x(int(f)) << "," << y(s->maePerFrame[f]);
        o << "\"><title>" << html(t->row.label) << "</title></polyline>";
        legend << "<span><i style=\"background:" << c << "\"></i>" << html(t->row.label)
               << "</span>";
    }
    o << "</svg><div class=\"legend\">" << legend.str() << "</div><p class=\"caption muted\">mae "
      << "of each of the " << frames << " frames against that frame's oracle "
      << "(docs/metrics.md#sequence); the rows above judge the last frame.</p></div>";
}

void writeHead(std::ostream& o, const ReportInput& in) {
    o << "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>shadow-oracle "
         "report: "
      << html(in.sceneFile) << "</title><style>" << report_assets::kStyle
      << "</style></head><body><h1>Shadow accuracy against the oracle: " << html(in.sceneFile)
      << "</h1><p>" << in.techniques.size() << " technique settings, " << in.lights.size()
      << " light" << (in.lights.size() == 1 ? "" : "s") << ". Times were measured on <b>"
      << html(in.timedOn) << "</b>";
    if (in.timedOn.find("llvmpipe") != std::string::npos)
        o << " (Mesa's CPU rasterizer: its times rank the techniques on this machine, not on a "
             "GPU)";
    o << "; medians over the timed frames, the techniques taking turns frame by frame. Files: "
         "<a href=\"metrics.json\">metrics.json</a> · <a href=\"metrics.csv\">metrics.csv</a> · "
         "<a href=\"metrics_wide.csv\">metrics_wide.csv</a> · <a "
         "href=\"oracle.exr\">oracle.exr</a>.</p><nav>Lights:";
    for (size_t li = 0; li < in.lights.size(); ++li)
        o << " <a href=\"#" << html(lightId(in, li)) << "\">" << html(in.lights[li]) << "</a>";
    o << " <a href=\"#all-metrics\">all metrics</a> <a href=\"#provenance\">run "
         "provenance</a></nav>";
}

// `lightsData`: every light's lightData, in order.
void writeTail(std::ostream& o, const ReportInput& in, const nlohmann::json& lightsData) {
    o << "<h2 id=\"all-metrics\">All metrics</h2>";
    writeAllMetrics(o, in);
    o << "<h2 id=\"provenance\">Run provenance</h2><table class=\"provenance\">";
    for (const auto& [key, value] : in.provenance)
        o << "<tr><th class=\"text\">" << html(key) << "</th><td class=\"text\">" << html(value)
          << "</td></tr>";
    o << "</table><div id=\"zoom\"><div class=\"bar\"><span id=\"zoom-title\"></span><button "
         "id=\"zoom-flip\">flip with the oracle (F)</button><label>scale <select "
         "id=\"zoom-scale\"><option>1</option><option selected>2</option><option>4</option>"
         "</select></label><button id=\"zoom-close\">close (Esc)</button></div><div "
         "class=\"view\"><canvas id=\"zoom-canvas\"></canvas></div></div>";
    std::string json = nlohmann::json({{"lights", lightsData}}).dump();
    for (size_t at = json.find("</"); at != std::string::npos; at = json.find("</", at + 2))
        json.replace(at, 2, "<\\/");
    o << "<script type=\"application/json\" id=\"so-data\">" << json << "</script><script>"
      << report_assets::kScript << "</script></body></html>\n";
}

}  // namespace

std::string oracleCertaintyNote(const ChannelImage& oracle, const std::string& light) {
    const std::string stdErrName = ch::lightChannel(light, ch::kStdErr);
    const std::string exactName = ch::lightChannel(light, ch::kExact);
    const float* stdErr = oracle.has(stdErrName) ? oracle.channel(stdErrName) : nullptr;
    const float* exact = oracle.has(exactName) ? oracle.channel(exactName) : nullptr;
    size_t sampled = 0, exactPixels = 0;
    for (size_t i = 0; i < oracle.pixelCount(); ++i) {
        if (exact && exact[i] > 0.5f)
            ++exactPixels;
        else if (stdErr && stdErr[i] > 0.0f)
            ++sampled;
    }
    const std::string interval =
        "an estimate with a 95% interval per pixel (V &plusmn; 2.36 &middot; stderr, "
        "docs/oracle.md); a technique's difference within that interval is not counted as error, "
        "and the magnitude map shows the error beyond it";
    std::ostringstream s;
    s << "<p class=\"note\">An area light: ";
    if (exactPixels == 0)
        s << "the oracle's V is " << interval << ".</p>";
    else if (sampled == 0)
        s << "the oracle's exact pass gave V at all " << exactPixels
          << " pixels it applied to, without sampling error (docs/oracle.md, \"Exact "
             "penumbrae\"); no pixel of this light carries a sampling interval.</p>";
    else
        s << "the oracle's exact pass gave V without sampling error at " << exactPixels
          << " pixels (docs/oracle.md, \"Exact penumbrae\"); at the other " << sampled
          << " penumbra pixels it is " << interval << ".</p>";
    return s.str();
}

void writeReport(const std::string& path, const ReportInput& in) {
    const std::filesystem::path page(path);
    const std::string folderName = page.stem().string() + "_images";
    ImageSink sink(in.embedImages ? std::filesystem::path() : page.parent_path() / folderName,
                   folderName);
    std::ostringstream o;
    writeHead(o, in);
    nlohmann::json lights = nlohmann::json::array();
    for (size_t li = 0; li < in.lights.size(); ++li) {
        lights.push_back(lightData(in, li));
        o << "<section class=\"light\" id=\"" << html(lightId(in, li)) << "\"><h2>Light "
          << html(in.lights[li]) << "</h2><div class=\"top\">";
        writeSummary(o, in, li);
        writeChartBox(o, in, li, lights.back());
        o << "</div>";
        writeContactPairs(o, in, li);
        writeImages(o, in, li, sink);
        writeFlickerStrip(o, in, li, sink);
        writeSequenceChart(o, in, li);
        o << "</section>";
    }
    writeTail(o, in, lights);
    std::ofstream f(path);
    if (!f) throwInputError(path, "", "cannot be written");
    f << o.str();
}

}  // namespace so
