#include "raster_compare/compare_command.h"

#include <unistd.h>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "core/channels.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/version.h"
#include "raster_compare/gl_context.h"
#include "raster_compare/metrics.h"
#include "raster_compare/report.h"
#include "raster_compare/technique.h"

namespace so {

namespace fs = std::filesystem;

TechniqueSpec parseTechniqueSpec(const std::string& spec) {
    TechniqueSpec t;
    t.label = spec;
    const auto colon = spec.find(':');
    t.name = spec.substr(0, colon);
    if (t.name.empty())
        throwInputError("command line", "--technique",
                        "empty technique name in \"" + printable(spec, 60) + "\"");
    if (colon != std::string::npos) {
        std::string rest = spec.substr(colon + 1);
        size_t start = 0;
        while (start <= rest.size()) {
            const size_t comma = rest.find(',', start);
            const std::string kv =
                rest.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
            if (!kv.empty()) t.settings.push_back(kv);
            if (comma == std::string::npos) break;
            start = comma + 1;
        }
    }
    for (char c : spec)
        t.fileLabel += (std::isalnum((unsigned char)c) || c == '-' || c == '.') ? c : '_';
    return t;
}

namespace {

fs::path defaultCacheDir() {
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x)
        return fs::path(x) / "shadow-oracle";
    if (const char* h = std::getenv("HOME"); h && *h)
        return fs::path(h) / ".cache" / "shadow-oracle";
    return fs::temp_directory_path() / "shadow-oracle-cache";
}

// The oracle's result is a function of the scene's content, the options that change it and the
// code that made it: all go into the key.
std::string oracleKey(const Scene& scene, const OracleOptions& o) {
    const CameraDesc cam = effectiveCamera(scene, o);
    const nlohmann::json k = {{"scene", scene.contentHash},
                              {"width", cam.width},
                              {"height", cam.height},
                              {"seed", o.area.seed},
                              {"target_error", o.area.targetError},
                              {"max_spp", o.area.maxSpp},
                              {"spp", o.area.fixedSpp},
                              {"verify", o.verify.pixels},
                              {"verify_samples", o.verify.areaSamples},
                              {"tool", std::string(kToolVersion) + " " + kGitRevision}};
    return hashBytes(k.dump());
}

void flatten(const nlohmann::json& j, const std::string& prefix,
             std::vector<std::pair<std::string, nlohmann::json>>& out) {
    for (auto it = j.begin(); it != j.end(); ++it) {
        const std::string name = prefix.empty() ? it.key() : prefix + "." + it.key();
        if (it->is_object())
            flatten(*it, name, out);
        else
            out.emplace_back(name, *it);
    }
}

std::string csvField(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

}  // namespace

int runCompareCommand(const CompareOptions& options) {
    // Everything the user can get wrong is checked before any work starts.
    std::vector<TechniqueSpec> specs;
    std::vector<ParamValues> params;
    for (const std::string& s : options.techniques) {
        specs.push_back(parseTechniqueSpec(s));
        const ShadowTechnique& t = findTechnique(specs.back().name);
        params.push_back(t.parse(specs.back().settings));
        t.shaderDefines(params.back());
    }
    Scene scene = loadScene(options.scenePath);
    for (const std::string& w : scene.stats.warnings)
        std::cerr << "warning: " << options.scenePath << ": " << w << "\n";
    const fs::path out(options.outDir);
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec) throwInputError(options.outDir, "--out", "cannot create the folder: " + ec.message());

    // The oracle, from the cache when the same scene content and options were traced before.
    OracleOptions oracleOptions = options.oracle;
    if (options.raster.width > 0) oracleOptions.width = options.raster.width;
    if (options.raster.height > 0) oracleOptions.height = options.raster.height;
    const std::string key = oracleKey(scene, oracleOptions);
    const fs::path cacheEntry =
        (options.cacheDir.empty() ? defaultCacheDir() : fs::path(options.cacheDir)) / key;
    ChannelImage oracleImage;
    nlohmann::json oracleStats;
    bool cached = false;
    if (options.useCache && fs::exists(cacheEntry / "oracle.exr") &&
        fs::exists(cacheEntry / "oracle.json")) {
        oracleImage = readExr((cacheEntry / "oracle.exr").string());
        std::ifstream in(cacheEntry / "oracle.json");
        oracleStats = nlohmann::json::parse(in, nullptr, false);
        cached = !oracleStats.is_discarded();
    }
    if (!cached) {
        OracleResult r = runOracle(scene, oracleOptions);
        oracleImage = std::move(r.image);
        oracleStats = std::move(r.stats);
        if (options.useCache) {
            // Written under a temporary name and renamed, so a crash never leaves half an entry.
            const fs::path tmp = cacheEntry.string() + ".tmp" + std::to_string(::getpid());
            fs::create_directories(tmp, ec);
            if (!ec) {
                writeExr((tmp / "oracle.exr").string(), oracleImage);
                std::ofstream(tmp / "oracle.json") << oracleStats.dump(2) << "\n";
                fs::remove_all(cacheEntry, ec);
                fs::rename(tmp, cacheEntry, ec);
                if (ec) fs::remove_all(tmp, ec);
            }
        }
    }
    writeExr((out / "oracle.exr").string(), oracleImage,
             {{"shadowOracle/sceneHash", scene.contentHash}});

    GlContext gl;
    const double extent = scene.wsBounds.extent();
    MetricOptions metricOptions;
    metricOptions.boundaryRadius = options.boundaryRadius;
    metricOptions.contactThreshold = options.contactThresholdRelative * extent;
    nlohmann::json results = nlohmann::json::array();
    ReportInput report;
    report.sceneFile = options.scenePath;
    for (const Light& l : scene.lights) report.lights.push_back(l.name);
    std::ofstream csv(out / "metrics.csv");
    csv << "scene,light,technique,label,metric,value\n";
    for (size_t t = 0; t < specs.size(); ++t) {
        const ShadowTechnique& technique = findTechnique(specs[t].name);
        std::cerr << "rendering " << specs[t].label << "\n";
        RasterResult r = renderRaster(scene, technique, params[t], options.raster, gl);
        const fs::path dir = out / specs[t].fileLabel;
        fs::create_directories(dir, ec);
        writeExr((dir / "raster.exr").string(), r.image,
                 {{"shadowOracle/technique", specs[t].label}});
        std::ofstream(dir / "raster.json") << r.stats.dump(2) << "\n";
        metricOptions.filteredTechnique = technique.filtered();
        ChannelImage errors(r.image.width(), r.image.height());
        ReportTechnique rt;
        rt.label = specs[t].label;
        nlohmann::json lights = nlohmann::json::object();
        for (size_t li = 0; li < scene.lights.size(); ++li) {
            const Light& light = scene.lights[li];
            ErrorMaps maps;
            LightMetrics m =
                computeLightMetrics(oracleImage, r.image, light.name, metricOptions, &maps);
            nlohmann::json lj = m.toJson();
            const auto& rl = r.stats["lights"][li];
            lj["cost"] = {{"shadow_map_ms", rl["shadow_map_ms"]},
                          {"visibility_ms", rl["visibility_ms"]},
                          {"frame_ms", r.stats["timings"]["wall_ms"]},
                          // What the ground truth cost, so every row carries both sides.
                          {"oracle_seconds", oracleStats["lights"][li].value("seconds", 0.0)}};
            lights[light.name] = lj;
            rt.lights.push_back(lj);
            const std::vector<float>* planes[] = {&maps.acne,     &maps.peterPanning,
                                                  &maps.aliasing, &maps.bleeding,
                                                  &maps.penumbra, &maps.error};
            const char* names[] = {"acne",     "peter_panning", "aliasing",
                                   "bleeding", "penumbra",      "error"};
            for (int k = 0; k < 6; ++k) {
                float* dst = errors.addChannel(light.name + "." + names[k]);
                std::copy(planes[k]->begin(), planes[k]->end(), dst);
            }
            rt.maps.push_back(std::move(maps));
            std::vector<std::pair<std::string, nlohmann::json>> rows;
            flatten(lj, "", rows);
            for (const auto& [metric, value] : rows)
                csv << csvField(options.scenePath) << ',' << csvField(light.name) << ','
                    << csvField(specs[t].name) << ',' << csvField(specs[t].label) << ',' << metric
                    << ',' << (value.is_null() ? "" : value.dump()) << "\n";
        }
        writeExr((out / ("error_" + specs[t].fileLabel + ".exr")).string(), errors);
        rt.image = std::move(r.image);
        report.techniques.push_back(std::move(rt));
        nlohmann::json paramJson = nlohmann::json::object();
        for (const auto& [k, v] : params[t]) paramJson[k] = v;
        results.push_back({{"technique", specs[t].name},
                           {"label", specs[t].label},
                           {"parameters", paramJson},
                           {"timings", r.stats["timings"]},
                           {"lights", lights}});
    }
    const nlohmann::json metrics = {
        {"schema_version", 1},
        {"tool",
         {{"name", "shadow-oracle"}, {"version", kToolVersion}, {"git_revision", kGitRevision}}},
        {"scene",
         {{"file", options.scenePath},
          {"hash", scene.contentHash},
          {"extent", extent},
          {"effects", scene.effects}}},
        {"options",
         {{"boundary_radius_px", options.boundaryRadius},
          {"contact_threshold", metricOptions.contactThreshold}}},
        {"oracle", {{"cached", cached}, {"key", key}, {"stats", oracleStats}}},
        {"gl",
         {{"renderer", gl.renderer()}, {"version", gl.version()}, {"platform", gl.platform()}}},
        {"results", results}};
    std::ofstream(out / "metrics.json") << metrics.dump(2) << "\n";
    report.oracle = std::move(oracleImage);
    report.provenance = {
        {"tool", metrics["tool"]}, {"scene_hash", scene.contentHash}, {"gl", metrics["gl"]}};
    writeReport((out / "report.html").string(), report);
    std::cout << "compared " << options.scenePath << ": " << specs.size() << " techniques, oracle "
              << (cached ? "from the cache" : "traced") << "\n  " << (out / "metrics.json").string()
              << "\n  " << (out / "metrics.csv").string() << "\n";
    // --verify: the oracle re-traced independently (docs/oracle.md#verification); a ground truth
    // that disagrees with it must not pass silently, cached or not.
    if (oracleStats.contains("verify")) {
        const uint64_t bad = oracleStats["verify"]["disagreements"].get<uint64_t>();
        std::cout << "  oracle verified: " << bad << " disagreements\n";
        if (bad) {
            std::cerr << "error: " << options.scenePath << ": verify: " << bad
                      << " pixels where the oracle disagrees with the exact re-trace (metrics.json "
                         "oracle.stats.verify)\n";
            return 3;
        }
    }
    return 0;
}

}  // namespace so
