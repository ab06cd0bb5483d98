#include "raster_compare/compare/contact_pairs.h"

#include <cstdio>

#include "raster_compare/compare/html.h"
#include "raster_compare/compare/result_row.h"

namespace so {

namespace {

// The parameters that configure the march: equal settings differ in them only when on.
bool isContactParameter(const std::string& name) {
    return name == "contact" || name.rfind("contact_", 0) == 0;
}

bool sameOtherParameters(const ResultRow& a, const ResultRow& b) {
    if (a.technique != b.technique) return false;
    auto other = [](const RowParameters& p) {
        RowParameters r;
        for (const auto& [k, v] : p)
            if (!isContactParameter(k)) r.emplace(k, v);
        return r;
    };
    return other(a.parameters) == other(b.parameters);
}

// contact=on or off (the method's index: off 0, on 1); none without the parameter.
std::optional<bool> contactOn(const ResultRow& s) {
    const auto it = s.parameters.find("contact");
    if (it == s.parameters.end()) return std::nullopt;
    return it->second.number != 0.0;
}

std::optional<double> difference(std::optional<double> a, std::optional<double> b) {
    if (!a || !b) return std::nullopt;
    return *a - *b;
}

std::string rate(std::optional<double> v) {
    if (!v) return "&ndash;";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4f", *v == 0.0 ? 0.0 : *v);  // no "-0.0000"
    return buf;
}

std::string change(std::optional<double> off, std::optional<double> on) {
    return rate(off) + " &rarr; " + rate(on);
}

}  // namespace

ContactRates contactRatesOf(const LightRow& l) {
    return {l.value("peter_panning_rate"), l.value("screen_bleed_rate"),
            l.value("false_shadow_rate"), l.value("acne_rate")};
}

std::optional<double> ContactPair::peterPanningClosed() const {
    return difference(off.peterPanning, on.peterPanning);
}
std::optional<double> ContactPair::screenBleedAdded() const {
    // A setting without a screen-space pass has no bleed: null off is none, not unmeasured.
    if (!on.screenBleed) return std::nullopt;
    return *on.screenBleed - off.screenBleed.value_or(0.0);
}
std::optional<double> ContactPair::falseShadowAdded() const {
    return difference(on.falseShadow, off.falseShadow);
}
std::optional<double> ContactPair::acneAdded() const {
    return difference(on.acne, off.acne);
}

std::vector<ContactPair> pairContactSettings(const std::vector<ContactSetting>& settings) {
    std::vector<ContactPair> pairs;
    for (const ContactSetting& on : settings) {
        if (contactOn(*on.setting) != true) continue;
        for (const ContactSetting& off : settings) {
            if (contactOn(*off.setting) != false || !sameOtherParameters(*on.setting, *off.setting))
                continue;
            pairs.push_back({off.setting->label, on.setting->label, contactRatesOf(*off.light),
                             contactRatesOf(*on.light)});
            break;
        }
    }
    return pairs;
}

void writeContactTable(std::ostream& o, const std::vector<ContactPair>& pairs) {
    if (pairs.empty()) return;
    o << "<div class=\"contact-box\"><h3>Contact shadows</h3><p class=\"muted\">Each setting "
         "with <code>contact=on</code> against the same setting with <code>contact=off</code> "
         "(docs/metrics.md#contact-shadows): the peter-panning the march closes (off &minus; "
         "on, positive is better) and the false shadow it adds (on &minus; off: screen-space "
         "bleed, the thickness guess's and steep slopes'; its acne should not move). &ndash;: "
         "not measured (peter-panning needs the scene's <code>contact</code> effect).</p>"
         "<table class=\"contact\"><thead><tr><th class=\"text\">contact=on</th><th "
         "class=\"text\">against</th><th>peter-panning off &rarr; on</th><th>closed</th><th>"
         "screen bleed off &rarr; on</th><th>bleed added</th><th>false shadow added</th><th>"
         "acne off &rarr; on</th></tr></thead><tbody>";
    // The differences also as attributes, to 9 significant digits, for scripts and tests to read.
    const auto attr = [](const char* name, std::optional<double> v) {
        if (!v) return std::string();
        char buf[64];
        std::snprintf(buf, sizeof buf, " %s=\"%.9g\"", name, *v);
        return std::string(buf);
    };
    for (const ContactPair& p : pairs)
        o << "<tr data-on=\"" << htmlEscape(p.onLabel) << "\""
          << attr("data-peter-panning-closed", p.peterPanningClosed())
          << attr("data-screen-bleed-added", p.screenBleedAdded())
          << attr("data-false-shadow-added", p.falseShadowAdded())
          << attr("data-acne-added", p.acneAdded()) << "><td class=\"text\">"
          << htmlEscape(p.onLabel) << "</td><td class=\"text\">" << htmlEscape(p.offLabel)
          << "</td><td>" << change(p.off.peterPanning, p.on.peterPanning) << "</td><td>"
          << rate(p.peterPanningClosed()) << "</td><td>"
          << change(p.off.screenBleed, p.on.screenBleed) << "</td><td>"
          << rate(p.screenBleedAdded()) << "</td><td>" << rate(p.falseShadowAdded()) << "</td><td>"
          << change(p.off.acne, p.on.acne) << "</td></tr>";
    o << "</tbody></table></div>";
}

}  // namespace so
