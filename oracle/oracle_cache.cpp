#include "oracle/oracle_cache.h"

#include <unistd.h>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/channels.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/version.h"
#include "oracle/trace_options.h"

namespace so {

namespace fs = std::filesystem;

fs::path defaultOracleCacheDir() {
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x)
        return fs::path(x) / "shadow-oracle";
    if (const char* h = std::getenv("HOME"); h && *h)
        return fs::path(h) / ".cache" / "shadow-oracle";
    return fs::temp_directory_path() / "shadow-oracle-cache";
}

nlohmann::json oracleSamplingJson(const OracleOptions& o, const CameraDesc& cam) {
    nlohmann::json j = resultOptionsJson(o, cam);
    j["exact_max_occluders"] = o.penumbra.maxOccluders;  // the exact pass's, not a table row
    return j;
}

// The oracle's result is a function of the scene's content, the options that change it (every
// trace option table row but those marked sameResult, by resultOptionsJson) and the code that made
// it: all go into the key. A change of the key's text invalidates the entries made before.
// (nlohmann::json keeps an object's keys sorted, so the key's text does not depend on the order in
// which they are added.)
std::string oracleCacheKey(const Scene& scene, const OracleOptions& o) {
    nlohmann::json k = oracleSamplingJson(o, effectiveCamera(scene, o));
    k["scene"] = scene.contentHash;
    k["tool"] = std::string(kToolVersion) + " " + kGitRevision;
    // A camera override (a path frame) sees other pixels. Only then is the pose in the key, so
    // the scene camera's entries keep the keys they had. Doubles as %.17g: exact round trip.
    if (o.camera) {
        char pose[400];
        const CameraDesc& c = *o.camera;
        std::snprintf(pose, sizeof pose,
                      "%.17g %.17g %.17g|%.17g %.17g %.17g|%.17g %.17g %.17g|%.17g", c.wsEye.x,
                      c.wsEye.y, c.wsEye.z, c.wsTarget.x, c.wsTarget.y, c.wsTarget.z, c.wsUp.x,
                      c.wsUp.y, c.wsUp.z, c.vfovDeg);
        k["camera"] = pose;
    }
    // A band of rows (trace --tile) is another image: in the key whenever set.
    if (o.rows) k["rows"] = {o.rows->begin, o.rows->end};
    return hashBytes(k.dump());
}

namespace {

// Why an entry that reads cannot be the one asked for (a collision, a hand-edited file), or "".
std::string staleReason(const CachedOracle& c, const Scene& scene, const OracleOptions& options) {
    const CameraDesc cam = effectiveCamera(scene, options);
    if (c.image.width() != cam.width || c.image.height() != cam.height)
        return "oracle.exr is " + std::to_string(c.image.width()) + "x" +
               std::to_string(c.image.height());
    if (c.stats.width != cam.width || c.stats.height != cam.height)
        return "oracle.json has another image size";
    if (c.stats.lights.size() != scene.lights.size()) return "oracle.json has other lights";
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const std::string& name = scene.lights[i].name;
        if (c.stats.lights[i].name != name) return "oracle.json has other lights";
        if (!c.image.has(channels::lightChannel(name, channels::kVisibility)))
            return "oracle.exr has no visibility for light " + name;
    }
    if (c.stats.verified() != (options.verify.pixels > 0))
        return options.verify.pixels > 0 ? "oracle.json is not verified, and verification is asked"
                                         : "oracle.json is verified, and verification is not asked";
    return "";
}

// Fills `out` from the entry; false (with a warning in out.warnings when the entry exists) if it
// cannot be used.
bool loadEntry(const fs::path& entry, const Scene& scene, const OracleOptions& options,
               CachedOracle& out) {
    const fs::path exr = entry / "oracle.exr", json = entry / "oracle.json";
    std::error_code ec;
    if (!fs::exists(exr, ec) || !fs::exists(json, ec)) return false;
    std::string why;
    try {
        out.image = readExr(exr.string());
        std::ifstream in(json);
        const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
        if (j.is_discarded()) throwInputError(json.string(), "", "invalid JSON");
        out.stats = oracleStatsFromJson(j, json.string());
        why = staleReason(out, scene, options);
    } catch (const InputError& e) {
        why = e.what();
    }
    if (why.empty()) return true;
    out.warnings.push_back("oracle cache entry " + entry.string() + " unusable (" + why +
                           "): tracing again");
    return false;
}

// Written under a temporary name and renamed, so a crash never leaves half an entry.
void storeEntry(const fs::path& entry, const ChannelImage& image, const OracleStats& stats,
                std::vector<std::string>& warnings) {
    static std::atomic<unsigned> counter{0};
    const fs::path tmp = entry.string() + ".tmp" + std::to_string(::getpid()) + "." +
                         std::to_string(counter.fetch_add(1));
    std::error_code ec;
    try {
        fs::create_directories(tmp, ec);
        if (ec) throw std::runtime_error("cannot create " + tmp.string() + ": " + ec.message());
        writeExr((tmp / "oracle.exr").string(), image);
        std::ofstream json(tmp / "oracle.json");
        json << toJson(stats).dump(2) << "\n";
        json.close();
        if (!json) throw std::runtime_error("cannot write " + (tmp / "oracle.json").string());
        fs::remove_all(entry, ec);
        fs::rename(tmp, entry, ec);
        if (ec)
            throw std::runtime_error("cannot rename to " + entry.string() + ": " + ec.message());
    } catch (const std::exception& e) {
        warnings.push_back("oracle cache: not stored (" + std::string(e.what()) + ")");
        fs::remove_all(tmp, ec);
    }
}

}  // namespace

CachedOracle traceOrLoad(const Scene& scene, const OracleOptions& oracle,
                         const OracleCacheOptions& cache) {
    CachedOracle out;
    out.key = oracleCacheKey(scene, oracle);
    const fs::path entry = (cache.dir.empty() ? defaultOracleCacheDir() : cache.dir) / out.key;
    if (cache.use && loadEntry(entry, scene, oracle, out)) {
        out.fromCache = true;
        return out;
    }
    OracleResult r = runOracle(scene, oracle);
    out.image = std::move(r.image);
    out.stats = std::move(r.stats);
    if (cache.use) storeEntry(entry, out.image, out.stats, out.warnings);
    return out;
}

}  // namespace so
