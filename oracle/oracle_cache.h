// The oracle's results kept on disk, so that a scene traced once with the same options is not
// traced again (the compare command). An entry is <dir>/<key>/oracle.exr + oracle.json, where
// oracle.json is toJson(stats); the key hashes the scene's content, every option that changes the
// result, and the tool's version and git revision.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/image.h"
#include "core/scene.h"
#include "oracle/oracle.h"
#include "oracle/oracle_stats.h"

namespace so {

struct OracleCacheOptions {
    std::filesystem::path dir;  // empty: defaultOracleCacheDir()
    bool use = true;            // false: always trace, store nothing
};

struct CachedOracle {
    ChannelImage image;
    OracleStats stats;
    bool fromCache = false;
    std::string key;
    // "oracle cache entry DIR unusable (why): tracing again", "oracle cache: not stored (why)":
    // for the caller to print (the library writes nothing to stderr).
    std::vector<std::string> warnings = {};
    // Traced at a G-buffer's points (trace --points), not at the camera's pixels: what only images
    // can be judged against (checkTechniquesAtPoints).
    bool atPoints = false;
};

// $XDG_CACHE_HOME/shadow-oracle, else ~/.cache/shadow-oracle, else the temp folder's
// shadow-oracle-cache.
std::filesystem::path defaultOracleCacheDir();

// The options besides the scene and the camera's pose that decide the pixels: the trace option
// table's rows that change the result (resultOptionsJson, oracle/trace_options.h) and the exact
// pass's occluder limit. The cache key and the `options` block of a tile's oracle.json
// (trace --tile) both start from it and add their own.
nlohmann::json oracleSamplingJson(const OracleOptions& options, const CameraDesc& cam);

// The entry's folder name: a hash of what the oracle's result is a function of.
std::string oracleCacheKey(const Scene& scene, const OracleOptions& options);

// The cached entry when present and readable (an unreadable or stale entry is traced again, with a
// warning in the result), else runOracle and store atomically (temp folder + rename) when
// options.use. A failure to store is a warning, not an error: the result is returned either way.
CachedOracle traceOrLoad(const Scene& scene, const OracleOptions& oracle,
                         const OracleCacheOptions& cache);

}  // namespace so
