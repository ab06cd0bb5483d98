#include "cli/gate_command.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli/output.h"
#include "core/error.h"
#include "raster_compare/compare/baseline.h"
#include "raster_compare/compare/gate.h"

namespace so {

using nlohmann::json;

namespace {

// Attribute text: labels come from the user (compare --image LABEL=PATH).
std::string xmlEscape(const std::string& s) {
    std::string o;
    for (char c : s) {
        switch (c) {
            case '&':
                o += "&amp;";
                break;
            case '<':
                o += "&lt;";
                break;
            case '>':
                o += "&gt;";
                break;
            case '"':
                o += "&quot;";
                break;
            default:
                // XML 1.0 has no other control characters, even escaped; a label may hold one.
                o += static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' ? '?' : c;
        }
    }
    return o;
}

std::string failureLine(const GateCheck& c) {
    std::ostringstream os;
    os << "FAIL " << c.scene << " " << c.light << " " << c.technique << " " << c.metric << " = "
       << *c.value << " > " << c.maximum;
    return os.str();
}

std::string number(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.4g", v);
    return b;
}

std::string signedNumber(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%+.4g", v);
    return b;
}

// "+0.0333, +270%": the change of the value (of |x| for a signed metric), and relative to the
// baseline where that is not 0.
std::string change(const BaselineCheck& c) {
    const double d = c.worsening();
    std::string s = signedNumber(d);
    const double base = c.better == Better::SmallerMagnitude ? std::fabs(*c.baseline) : *c.baseline;
    if (base != 0.0) {
        char b[32];
        std::snprintf(b, sizeof b, "%+.0f%%", 100.0 * d / std::fabs(base));
        s += std::string(", ") + b;
    }
    return s;
}

std::string rowName(const std::string& scene, const std::string& light, const std::string& label) {
    return scene + " " + light + " " + label;
}

std::string toleranceText(const BaselineCheck& c) {
    std::string s =
        "abs " + number(c.tolerance.abs) + " + rel " + number(100.0 * c.tolerance.rel) + "%";
    if (c.noise > 0.0) s += " + oracle noise " + number(c.noise);
    return s;
}

std::string regressionLine(const BaselineCheck& c) {
    return "REGRESSED " + rowName(c.scene, c.light, c.label) + " " + c.metric +
           (c.better == Better::SmallerMagnitude ? " (|x|)" : "") + ": " + number(*c.baseline) +
           " -> " + number(*c.value) + " (" + change(c) + ") beyond tolerance " + toleranceText(c);
}

std::string limitsSuite(const std::vector<GateCheck>& checks, size_t failures) {
    std::ostringstream x;
    x << "  <testsuite name=\"shadow-oracle gate\" tests=\"" << checks.size() << "\" failures=\""
      << failures << "\">\n";
    for (const GateCheck& c : checks) {
        x << "    <testcase classname=\"" << xmlEscape(c.scene + "." + c.light) << "\" name=\""
          << xmlEscape(c.technique + " " + c.metric) << "\"";
        if (!c.value)
            x << ">\n      <skipped message=\"null: not applicable here\"/>\n    </testcase>\n";
        else if (!c.failed())
            x << "/>\n";
        else
            x << ">\n      <failure message=\"" << xmlEscape(failureLine(c))
              << "\"/>\n    </testcase>\n";
    }
    x << "  </testsuite>\n";
    return x.str();
}

// One testcase per compared (scene, light, label, metric), and one per row present in one run
// only: a failure for a missing row, skipped (with the note) for a new one.
std::string baselineSuite(const BaselineComparison& b) {
    std::ostringstream x;
    const size_t tests = b.checks.size() + b.missing.size() + b.added.size();
    x << "  <testsuite name=\"shadow-oracle gate baseline\" tests=\"" << tests << "\" failures=\""
      << b.regressions() + b.missing.size() << "\">\n";
    for (const BaselineCheck& c : b.checks) {
        x << "    <testcase classname=\"" << xmlEscape(c.scene + "." + c.light) << "\" name=\""
          << xmlEscape(c.label + " " + c.metric + " (baseline)") << "\"";
        if (!c.applicable())
            x << ">\n      <skipped message=\"null in "
              << (c.baseline ? "the new run"
                  : c.value  ? "the baseline"
                             : "both runs")
              << ": not compared\"/>\n    </testcase>\n";
        else if (!c.regressed())
            x << "/>\n";
        else
            x << ">\n      <failure message=\"" << xmlEscape(regressionLine(c))
              << "\"/>\n    </testcase>\n";
    }
    for (const BaselineRow& r : b.missing)
        x << "    <testcase classname=\"" << xmlEscape(r.scene + "." + r.light) << "\" name=\""
          << xmlEscape(r.label + " (row)") << "\">\n      <failure message=\""
          << xmlEscape("MISSING in new: " + rowName(r.scene, r.light, r.label))
          << "\"/>\n    </testcase>\n";
    for (const BaselineRow& r : b.added)
        x << "    <testcase classname=\"" << xmlEscape(r.scene + "." + r.light) << "\" name=\""
          << xmlEscape(r.label + " (row)") << "\">\n      <skipped message=\""
          << xmlEscape("NEW: " + rowName(r.scene, r.light, r.label) + ": no baseline")
          << "\"/>\n    </testcase>\n";
    x << "  </testsuite>\n";
    return x.str();
}

// Markdown table cells: a label comes from the user, so '|' is escaped and HTML cannot open.
std::string cell(const std::string& s) {
    std::string o;
    for (char c : s) {
        if (c == '|')
            o += "\\|";
        else if (c == '<')
            o += "&lt;";
        else if (c == '>')
            o += "&gt;";
        else if (static_cast<unsigned char>(c) < 0x20)
            o += ' ';
        else
            o += c;
    }
    return o;
}

void writeSummary(const std::string& path, const std::vector<GateCheck>* limits,
                  size_t limitFailures, const BaselineComparison* b) {
    std::ostringstream md;
    const size_t regressed = b ? b->regressions() : 0, missing = b ? b->missing.size() : 0;
    const bool failed = limitFailures || regressed || missing;
    md << "### shadow-oracle gate: " << (failed ? "FAILED" : "passed") << "\n\n";
    if (limits) {
        md << "Limits: " << limits->size() - limitFailures << " passed, " << limitFailures
           << " failed.\n\n";
        for (const GateCheck& c : *limits)
            if (c.failed()) md << "- `" << cell(failureLine(c)) << "`\n";
        if (limitFailures) md << "\n";
    }
    if (b) {
        size_t improved = 0, unchanged = 0, na = 0;
        for (const BaselineCheck& c : b->checks) {
            improved += c.improved();
            na += !c.applicable();
            unchanged += c.applicable() && !c.improved() && !c.regressed();
        }
        md << "Against the baseline: **" << regressed << " worse**, " << missing
           << (missing == 1 ? " row" : " rows") << " missing in the new run, " << improved
           << " better, " << unchanged << " unchanged within tolerance, " << na
           << " not applicable (null), " << b->added.size()
           << (b->added.size() == 1 ? " new row" : " new rows") << ".\n\n";
        if (regressed + improved + missing + b->added.size()) {
            md << "| | scene | light | label | metric | baseline | new | change | tolerance |\n"
                  "|---|---|---|---|---|---|---|---|---|\n";
            for (int pass = 0; pass < 2; ++pass)
                for (const BaselineCheck& c : b->checks)
                    if (pass == 0 ? c.regressed() : c.improved())
                        md << "| " << (pass == 0 ? "worse" : "better") << " | " << cell(c.scene)
                           << " | " << cell(c.light) << " | " << cell(c.label) << " | `" << c.metric
                           << "`" << (c.better == Better::SmallerMagnitude ? " (|x|)" : "") << " | "
                           << number(*c.baseline) << " | " << number(*c.value) << " | " << change(c)
                           << " | " << toleranceText(c) << " |\n";
            for (const BaselineRow& r : b->missing)
                md << "| missing in new | " << cell(r.scene) << " | " << cell(r.light) << " | "
                   << cell(r.label) << " | | | | | |\n";
            for (const BaselineRow& r : b->added)
                md << "| new (no baseline) | " << cell(r.scene) << " | " << cell(r.light) << " | "
                   << cell(r.label) << " | | | | | |\n";
        }
    }
    std::ofstream out(path);
    if (!out) throwInputError(path, "--summary", "cannot be written");
    out << md.str();
}

}  // namespace

int runGateCommand(const GateOptions& options) {
    if (options.limitsPath.empty() && options.baselinePath.empty())
        throwInputError(options.metricsPath, "--limits", "give --limits, --baseline or both");
    const json metrics = readJsonFile(options.metricsPath, "metrics");
    std::optional<json> limits;
    if (!options.limitsPath.empty()) limits = readJsonFile(options.limitsPath, "limits");
    std::vector<GateCheck> checks;
    size_t failures = 0;
    if (limits) {
        checks = evaluateGate(metrics, options.metricsPath, *limits, options.limitsPath);
        for (const GateCheck& c : checks)
            if (c.failed()) {
                std::cout << failureLine(c) << "\n";
                ++failures;
            }
        size_t notApplicable = 0;
        for (const GateCheck& c : checks) notApplicable += !c.value;
        std::cout << checks.size() - failures << " passed";
        if (notApplicable)
            std::cout << " (" << notApplicable
                      << " of them not applicable: the metric is null there)";
        std::cout << ", " << failures << " failed\n";
    }
    std::optional<BaselineComparison> b;
    if (!options.baselinePath.empty()) {
        const json old = readJsonFile(options.baselinePath, "baseline metrics");
        b = compareToBaseline(metrics, options.metricsPath, old, options.baselinePath,
                              limits ? &*limits : nullptr, options.limitsPath);
        size_t improved = 0, na = 0;
        for (const BaselineCheck& c : b->checks) {
            if (c.regressed()) std::cout << regressionLine(c) << "\n";
            improved += c.improved();
            na += !c.applicable();
        }
        for (const BaselineRow& r : b->missing)
            std::cout << "MISSING in new: " << rowName(r.scene, r.light, r.label)
                      << " (in the baseline; fails)\n";
        for (const BaselineRow& r : b->added)
            std::cout << "NEW: " << rowName(r.scene, r.light, r.label)
                      << " (no baseline; not compared)\n";
        std::cout << "baseline: " << b->checks.size() << " compared, " << b->regressions()
                  << " regressed, " << improved << " improved, " << na << " not applicable (null); "
                  << b->missing.size() << " rows missing in new, " << b->added.size() << " new\n";
    }
    if (!options.junitPath.empty()) {
        std::ofstream x(options.junitPath);
        if (!x) throwInputError(options.junitPath, "--junit", "cannot be written");
        x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites>\n";
        if (limits) x << limitsSuite(checks, failures);
        if (b) x << baselineSuite(*b);
        x << "</testsuites>\n";
    }
    if (!options.summaryPath.empty())
        writeSummary(options.summaryPath, limits ? &checks : nullptr, failures, b ? &*b : nullptr);
    return failures || (b && b->failed()) ? 1 : 0;
}

}  // namespace so
