// `shadow-oracle trace`: load, run the oracle, write oracle.exr, oracle.json and NAME.png
// previews (docs/cli.md, docs/oracle.md).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "oracle/oracle.h"

namespace so {

struct TraceCommandOptions {
    std::string scenePath;
    std::string outDir;
    OracleOptions oracle;  // its progress callback is the command's own bar
    bool progress = true;  // --quiet: false
    // --tile I/N: trace only band I of N bands of rows (oracle.h tileRows); empty: the whole
    // image. Parsed by runTraceCommand, which sets oracle.rows.
    std::string tile;
    // --points GBUFFER.exr: the oracle at the G-buffer's points (oracle/points.h) instead of the
    // camera's primary hits; empty: a plain trace.
    std::string pointsPath;
    // --no-previews: false. The PNG previews are the only images trace encodes, so without them
    // OpenImageIO's module (~0.2 s to load, docs/benchmarks.md) is never loaded.
    bool previews = true;
};

// Returns the process exit code; InputError propagates to main (exit 2).
int runTraceCommand(const TraceCommandOptions& options);

// "I/N" with 0 <= I < N <= kMaxTiles, or an InputError naming --tile.
struct TileSpec {
    int index = 0, count = 1;
};
inline constexpr int kMaxTiles = 4096;
// The EXR attribute naming a band's tile ("I/N"); the merged file has none.
inline constexpr const char* kTileAttribute = "shadowOracle/tile";
TileSpec parseTileSpec(const std::string& text);

// The options that decide the pixels, as a tile's oracle.json records them ("tile.options"):
// trace-merge joins only tiles whose options are equal.
nlohmann::json tracedOptionsJson(const OracleOptions& options, const CameraDesc& camera);

// Shaded preview of one light: grey Lambert with a little ambient, times V, so a person sees the
// shadows (and the attached-shadow side) at a glance.
}  // namespace so
