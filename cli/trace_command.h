// `shadow-oracle trace`: load, run the oracle, write oracle.exr, oracle.json and NAME.png
// previews (docs/cli.md, docs/oracle.md) through oracle/trace_output.h; this parses and prints.
#pragma once

#include <string>

#include "oracle/oracle.h"
#include "oracle/trace_output.h"

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
    // --frame K: the scene of a sequence at frame K (core/scene_pose.h), written into outDir;
    // --frames A:B: frames A to B, both included, each into outDir/frame_NNNN/. Empty: the scene as
    // loaded. Parsed and checked by runTraceCommand.
    std::string frame;
    std::string frames;
};

// Returns the process exit code; InputError propagates to main (exit 2).
int runTraceCommand(const TraceCommandOptions& options);

// "I/N" with 0 <= I < N <= kMaxTiles (oracle/trace_output.h), or an InputError naming --tile.
TileSpec parseTileSpec(const std::string& text);

}  // namespace so
