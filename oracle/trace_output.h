// The trace command's output folder (docs/oracle.md, docs/cli.md): oracle.exr, oracle.json and a
// NAME.png preview per light, written from a typed OracleResult. The command, the C++ API
// (writeTraceOutput) and Python write the same files through here, so `trace-merge`, `gate` and a
// sweep read them alike. In the oracle's library: writing a trace needs no GL.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/scene.h"
#include "oracle/oracle.h"

namespace so {

// oracle.json's format_version (docs/oracle.md lists what each version added).
inline constexpr int kOracleJsonFormatVersion = 14;

// `trace --tile I/N`: band I of N bands of rows (tileRows).
struct TileSpec {
    int index = 0, count = 1;
};
inline constexpr int kMaxTiles = 4096;
// The EXR attribute naming a band's tile ("I/N"); the merged file has none.
inline constexpr const char* kTileAttribute = "shadowOracle/tile";

// The options that decide the pixels, as a tile's oracle.json records them ("tile.options"):
// trace-merge joins only tiles whose options are equal.
nlohmann::json tracedOptionsJson(const OracleOptions& options, const CameraDesc& camera);

// A frame of the scene's sequence (`trace --frame K`): oracle.json's sequence_frame.
struct SequenceFrame {
    int index = 0;   // K
    double t = 0.0;  // seconds: K / fps
};

// What oracle.json says beyond the result itself.
struct TraceOutputOptions {
    std::string scenePath;     // scene.file: the path as the caller gave it
    double loadSeconds = 0.0;  // phases_seconds.load
    bool previews = true;      // the NAME.png previews (libraries.png is null without them)
    // The band this result is (options.rows is its tileRows); none: the whole image.
    std::optional<TileSpec> tile;
    ProgressCallback progress;  // "writing <dir>/oracle.exr"
    // The sequence's frame the scene was posed at; none: the scene as its file has it.
    std::optional<SequenceFrame> frame;
};

struct TraceOutputFiles {
    std::filesystem::path exr, json;
    std::vector<std::string> previews;
};

// Writes the folder `dir` (created if missing; an InputError naming it when it cannot be) for
// `result`, traced from `scene` with `options` (runOracle, or runOracleAtPoints when
// result.points is set). phases_seconds.write_exr, write_previews and process are this call's.
TraceOutputFiles writeTraceOutput(const std::filesystem::path& dir, const Scene& scene,
                                  const OracleOptions& options, const OracleResult& result,
                                  const TraceOutputOptions& output);

}  // namespace so
