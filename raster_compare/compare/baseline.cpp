#include "raster_compare/compare/baseline.h"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <utility>

#include "core/error.h"
#include "core/json_reader.h"
#include "raster_compare/compare/gate.h"
#include "raster_compare/compare/metrics.h"
#include "raster_compare/compare/result_row.h"

namespace so {

using nlohmann::json;

const std::vector<const MetricInfo*>& baselineMetricTable() {
    static const std::vector<const MetricInfo*> table = [] {
        std::vector<const MetricInfo*> out;
        for (const MetricInfo& m : allMetrics())
            if (m.baseline.use == BaselineRule::ByDefault) out.push_back(&m);
        // The costs as the reports order their axes: frame time, the passes' times, the other
        // times (camera, bake), memory, work.
        using A = CostAxis;
        for (const A kind : {A::Frame, A::Pass, A::None, A::Memory, A::Work})
            for (const MetricInfo& m : allMetrics())
                if (m.baseline.use == BaselineRule::WhenNamed && m.costAxis == kind)
                    out.push_back(&m);
        return out;
    }();
    return table;
}

bool takesFileDefault(const MetricInfo& m) {
    return m.unit == MetricUnit::V || m.unit == MetricUnit::Share;
}

namespace {

// The value as a score where larger is worse, by the metric table's direction.
double score(Better b, double v) {
    switch (b) {
        case Better::SmallerMagnitude:
            return std::fabs(v);
        case Better::Higher:
            return -v;
        case Better::Lower:
        case Better::None:
            break;
    }
    return v;
}

}  // namespace

double BaselineCheck::worsening() const {
    return score(better, *value) - score(better, *baseline);
}

double BaselineCheck::allowed() const {
    return tolerance.abs + tolerance.rel * std::fabs(score(better, *baseline)) + noise;
}

size_t BaselineComparison::regressions() const {
    size_t n = 0;
    for (const BaselineCheck& c : checks) n += c.regressed();
    return n;
}

namespace {

const MetricInfo* findCompared(const std::string& name) {
    for (const MetricInfo* m : baselineMetricTable())
        if (name == m->name) return m;
    return nullptr;
}

Tolerance readTolerance(const json& j, const std::string& lf, const std::string& field,
                        Tolerance t) {
    const JsonReader r(lf);
    r.checkKeys(j, field, {"abs", "rel"});
    for (auto it = j.begin(); it != j.end(); ++it)
        (it.key() == "abs" ? t.abs : t.rel) = r.numberAtLeast(*it, field + "." + it.key(), 0.0);
    return t;
}

}  // namespace

BaselineSettings readBaselineSettings(const json* limits, const std::string& lf) {
    const json empty = json::object();
    const json* b = &empty;
    if (limits && limits->is_object() && limits->contains("baseline")) {
        const auto format = limits->find("limits_format");
        if (format == limits->end() || !format->is_number() || format->get<double>() != 2.0)
            throwInputError(lf, "baseline", "needs limits_format 2");
        b = &(*limits)["baseline"];
    }
    const JsonReader r(lf);
    r.checkKeys(*b, "baseline", {"default", "metrics", "ignore"});
    std::optional<Tolerance> fileDefault;
    if (b->contains("default"))
        fileDefault = readTolerance((*b)["default"], lf, "baseline.default", {0.001, 0.05});
    std::map<const MetricInfo*, Tolerance> named;
    if (b->contains("metrics")) {
        const json& ms = (*b)["metrics"];
        r.requireObject(ms, "baseline.metrics");
        for (auto it = ms.begin(); it != ms.end(); ++it) {
            const std::string f = "baseline.metrics." + printable(it.key(), 60);
            const MetricInfo* m = findCompared(it.key());
            if (!m)
                throwInputError(lf, f,
                                "not a metric the baseline compares (docs/gate.md#baseline)");
            Tolerance t = m->baseline.tolerance;
            if (fileDefault && takesFileDefault(*m)) t = *fileDefault;
            named[m] = readTolerance(*it, lf, f, t);
        }
    }
    std::set<const MetricInfo*> ignored;
    if (b->contains("ignore")) {
        const json& ig = (*b)["ignore"];
        r.requireArray(ig, "baseline.ignore");
        for (size_t i = 0; i < ig.size(); ++i) {
            const std::string f = JsonReader::index("baseline.ignore", i);
            const MetricInfo* m = findCompared(r.string(ig[i], f));
            if (!m)
                throwInputError(lf, f,
                                "not a metric the baseline compares (docs/gate.md#baseline)");
            if (named.count(m))
                throwInputError(lf, f, "both ignored and named in baseline.metrics");
            ignored.insert(m);
        }
    }
    BaselineSettings s;
    for (const MetricInfo* m : baselineMetricTable()) {
        if (ignored.count(m)) continue;
        if (named.count(m)) {
            s.compared.emplace_back(m, named[m]);
        } else if (m->baseline.use == BaselineRule::ByDefault) {
            s.compared.emplace_back(
                m, fileDefault && takesFileDefault(*m) ? *fileDefault : m->baseline.tolerance);
        }
    }
    return s;
}

namespace {

// The sampled oracle's stated uncertainty per light, from metrics.json's oracle.stats.lights[]
// (docs/oracle.md): the mean 95% half-width over the penumbra's pixels at the end of the run (the
// last cost_curve point) and the worst pixel's. Hard lights (exact, no cost curve) have none.
struct OracleUncertainty {
    double meanHalfWidth = 0.0, worstHalfWidth = 0.0;
};

double optionalNumber(const json& o, const char* key, const JsonReader& r,
                      const std::string& field) {
    const json* v = JsonReader::find(o, key);
    if (!v || v->is_null()) return 0.0;
    return r.numberAtLeast(*v, field + "." + key, 0.0);
}

std::map<std::string, OracleUncertainty> oracleUncertainty(const json& metrics,
                                                           const std::string& path) {
    std::map<std::string, OracleUncertainty> out;
    const auto oracle = metrics.find("oracle");
    if (oracle == metrics.end() || !oracle->is_object()) return out;
    const auto stats = oracle->find("stats");
    if (stats == oracle->end() || !stats->is_object()) return out;
    const auto lights = stats->find("lights");
    if (lights == stats->end()) return out;
    const JsonReader r(path);
    r.requireArray(*lights, "oracle.stats.lights");
    for (size_t i = 0; i < lights->size(); ++i) {
        const std::string f = JsonReader::index("oracle.stats.lights", i);
        const json& l = (*lights)[i];
        const std::string name = r.string(r.at(l, f, "name"), f + ".name");
        OracleUncertainty u;
        u.worstHalfWidth = optionalNumber(l, "worst_half_width", r, f);
        const json* curve = JsonReader::find(l, "cost_curve");
        if (curve && !curve->is_null()) {
            r.requireArray(*curve, f + ".cost_curve");
            if (!curve->empty()) {
                const std::string pf = JsonReader::index(f + ".cost_curve", curve->size() - 1);
                const json& last = curve->back();
                r.requireObject(last, pf);
                u.meanHalfWidth = optionalNumber(last, "penumbra_mean_half_width", r, pf);
                if (u.meanHalfWidth == 0.0)  // no penumbra pixels: the mean over all sampled ones
                    u.meanHalfWidth = optionalNumber(last, "mean_half_width", r, pf);
            }
        }
        out[name] = u;
    }
    return out;
}

using RowKey = std::tuple<std::string, std::string, std::string>;  // scene file name, light, label

struct Run {
    std::map<RowKey, LightRow> rows;
    std::vector<RowKey> order;
    std::map<RowKey, int> seen;  // rows so far with that (scene, light, label)
    // Rows that build over frames: history_frames and where the file says it ("results[2]").
    std::map<RowKey, std::pair<int, std::string>> history;
    std::map<std::string, OracleUncertainty> uncertainty;
};

Run readRun(const json& metrics, const std::string& path) {
    checkMetricsShape(metrics, path);
    Run run;
    const auto sceneObject = metrics.find("scene");
    const std::string scene =
        std::filesystem::path(sceneObject == metrics.end() ? std::string()
                                                           : sceneObject->value("file", ""))
            .filename()
            .string();
    const json& results = metrics["results"];
    const JsonReader r(path);
    for (size_t i = 0; i < results.size(); ++i) {
        ResultRow row = readResultRow(results[i], r, JsonReader::index("results", i));
        for (LightRow& light : row.lights) {
            // The same label twice in one run (compare --technique basic --technique basic): the
            // n-th matches the other run's n-th, shown as LABEL#n.
            const int first = ++run.seen[{scene, light.light, row.label}];
            const std::string l = light.light;
            RowKey key{scene, l, first == 1 ? row.label : row.label + "#" + std::to_string(first)};
            for (int n = first + 1; run.rows.count(key); ++n)  // past a label "basic#2" itself
                key = {scene, l, row.label + "#" + std::to_string(n)};
            if (row.historyFrames)
                run.history[key] = {*row.historyFrames, JsonReader::index("results", i)};
            run.rows[key] = std::move(light);
            run.order.push_back(key);
        }
    }
    run.uncertainty = oracleUncertainty(metrics, path);
    return run;
}

// A row that builds over frames judged after as many frames in both runs: a converged image
// against a cold one is another image, not a regression or an improvement (docs/gate.md#baseline).
void checkSameHistory(const Run& now, const std::string& metricsPath, const Run& before,
                      const std::string& baselinePath) {
    for (const auto& [key, frames] : now.history) {
        const auto old = before.history.find(key);
        if (old == before.history.end() || old->second.first == frames.first) continue;
        const auto said = [](int n) {
            return n == 0 ? std::string("0 (a cold start)") : std::to_string(n);
        };
        throwInputError(metricsPath, frames.second + ".history_frames",
                        said(frames.first) + " for \"" + printable(std::get<2>(key), 60) + "\", " +
                            said(old->second.first) + " in the baseline " + baselinePath +
                            ": cold and converged images differ; run both with the same "
                            "compare --converge N");
    }
}

// Versions whose metrics mean the same (docs/metrics.md, Versions): 4 and 5 (5 adds rows of
// external images, not new definitions), 6 and 7 (7 adds cost.work); each other one only with
// itself (6 moves an area light's over-wide penumbra out of acne_rate, 8 classes acne by its
// cause).
int64_t metricsEpoch(int64_t version) {
    return version == 5 ? 4 : version == 7 ? 6 : version;
}

}  // namespace

BaselineComparison compareToBaseline(const json& metrics, const std::string& metricsPath,
                                     const json& baseline, const std::string& baselinePath,
                                     const json* limits, const std::string& limitsPath) {
    const Run now = readRun(metrics, metricsPath), before = readRun(baseline, baselinePath);
    const int64_t vNew = metrics["schema_version"].get<int64_t>(),
                  vOld = baseline["schema_version"].get<int64_t>();
    if (metricsEpoch(vNew) != metricsEpoch(vOld))
        throwInputError(baselinePath, "schema_version",
                        std::to_string(vOld) + " and the new run's " + std::to_string(vNew) +
                            " define the metrics differently (docs/metrics.md, Versions): rerun "
                            "the baseline with this version");
    const BaselineSettings settings = readBaselineSettings(limits, limitsPath);
    checkSameHistory(now, metricsPath, before, baselinePath);
    BaselineComparison out;
    for (const RowKey& key : now.order) {
        const auto old = before.rows.find(key);
        const auto& [scene, light, label] = key;
        if (old == before.rows.end()) {
            out.added.push_back({scene, light, label});
            continue;
        }
        const LightRow& rowNew = now.rows.at(key);
        const auto uNew = now.uncertainty.find(light), uOld = before.uncertainty.find(light);
        const OracleUncertainty un = uNew == now.uncertainty.end() ? OracleUncertainty{}
                                                                   : uNew->second,
                                uo = uOld == before.uncertainty.end() ? OracleUncertainty{}
                                                                      : uOld->second;
        for (const auto& [metric, tolerance] : settings.compared) {
            // In neither run: a temporal metric without a camera path.
            if (!old->second.has(*metric) && !rowNew.has(*metric)) continue;
            BaselineCheck c{scene,
                            light,
                            label,
                            metric->name,
                            old->second.value(*metric),
                            rowNew.value(*metric),
                            metric->better,
                            tolerance,
                            0.0};
            if (metric->baseline.noise == OracleNoise::MeanHalfWidth)
                c.noise = std::hypot(un.meanHalfWidth, uo.meanHalfWidth);
            else if (metric->baseline.noise == OracleNoise::WorstHalfWidth)
                c.noise = std::hypot(un.worstHalfWidth, uo.worstHalfWidth);
            out.checks.push_back(std::move(c));
        }
    }
    for (const RowKey& key : before.order)
        if (!now.rows.count(key))
            out.missing.push_back({std::get<0>(key), std::get<1>(key), std::get<2>(key)});
    return out;
}

}  // namespace so
