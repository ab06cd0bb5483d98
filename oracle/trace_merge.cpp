#include "oracle/trace_merge.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <thread>

#include <nlohmann/json.hpp>

#include "core/channels.h"
#include "core/error.h"
#include "core/image_codec.h"
#include "core/json_file.h"
#include "core/json_reader.h"
#include "core/png_encode.h"
#include "core/preview.h"
#include "oracle/oracle.h"
#include "oracle/oracle_stats.h"
#include "oracle/trace_merge_stats.h"
#include "oracle/trace_output.h"

namespace so {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// One band as trace --tile wrote it.
struct Tile {
    fs::path dir;
    std::string jsonPath;  // for messages
    json j;                // its oracle.json
    TileSpec spec;
    RowBand rows;
    ExrFile exr;
};

// "/tile/index" as errors name the field: "tile.index".
std::string fieldName(const char* pointer) {
    std::string field = std::string(pointer).substr(1);
    std::replace(field.begin(), field.end(), '/', '.');
    return field;
}

int intAt(const json& j, const std::string& path, const char* pointer) {
    const JsonReader r(path);
    const json::json_pointer p(pointer);
    if (!j.contains(p)) r.fail(fieldName(pointer), "missing");
    return r.integer(j.at(p), fieldName(pointer), std::numeric_limits<int>::min(),
                     std::numeric_limits<int>::max());
}

Tile readTile(const std::string& dir) {
    Tile t;
    t.dir = dir;
    t.jsonPath = (t.dir / "oracle.json").string();
    t.j = readJsonFile(t.jsonPath, "not an output folder of trace --tile?");
    if (!t.j.is_object() || !t.j.contains("tile"))
        throwInputError(t.jsonPath, "tile", "missing: not written by trace --tile");
    const JsonReader r(t.jsonPath);
    t.spec = {intAt(t.j, t.jsonPath, "/tile/index"), intAt(t.j, t.jsonPath, "/tile/count")};
    const json& rows = r.at(t.j["tile"], "tile", "rows");
    if (!rows.is_array() || rows.size() != 2)
        r.fail("tile.rows", "expected [first row, end row], got " + JsonReader::typeName(rows));
    t.rows = {r.integer(rows[0], "tile.rows[0]", 0, std::numeric_limits<int>::max()),
              r.integer(rows[1], "tile.rows[1]", 0, std::numeric_limits<int>::max())};
    t.exr = readExrFile((t.dir / "oracle.exr").string());
    return t;
}

// `field` (a JSON pointer) must be the same in `t` as in the first band.
void checkSame(const Tile& first, const Tile& t, const char* pointer) {
    const json::json_pointer p(pointer);
    const json a = first.j.contains(p) ? first.j.at(p) : json();
    const json b = t.j.contains(p) ? t.j.at(p) : json();
    if (a == b) return;
    throwInputError(t.jsonPath, fieldName(pointer),
                    printable(b.dump(), 60) + " differs from " + printable(a.dump(), 60) + " in " +
                        first.jsonPath + ": the tiles are not of one trace");
}

// Same scene, image, options and tool as the first band, and the band where it must be.
void checkBelongs(const Tile& first, const Tile& t) {
    for (const char* field :
         {"/scene/hash", "/tool", "/libraries/embree", "/image", "/effects", "/tile/count"})
        checkSame(first, t, field);
    if (!t.j.at("tile").contains("options") || !t.j["tile"]["options"].is_object())
        throwInputError(t.jsonPath, "tile.options", "missing");
    const json& options = first.j["tile"]["options"];
    for (auto it = options.begin(); it != options.end(); ++it)
        checkSame(first, t, ("/tile/options/" + it.key()).c_str());
    checkSame(t, first, "/tile/options");  // and no option only this band has
    const int width = intAt(t.j, t.jsonPath, "/image/width");
    const int height = intAt(t.j, t.jsonPath, "/image/height");
    const TileSpec s = t.spec;
    if (s.count < 1 || s.count > kMaxTiles || s.count > tileRowCount(height) || s.index < 0 ||
        s.index >= s.count)
        throwInputError(t.jsonPath, "tile.index",
                        std::to_string(s.index) + "/" + std::to_string(s.count) +
                            " is not a band of an image " + std::to_string(height) + " high");
    if (t.rows != tileRows(height, s.index, s.count))
        throwInputError(t.jsonPath, "tile.rows", "not the rows of band " + std::to_string(s.index));
    const ExrFile& e = t.exr;
    if (e.fullWidth != width || e.columnBegin != 0 || e.image.width() != width ||
        e.rows.fullHeight != height || e.rows.rowBegin != t.rows.begin ||
        e.image.height() != t.rows.count())
        throwInputError((t.dir / "oracle.exr").string(), "data window",
                        "does not hold rows " + std::to_string(t.rows.begin) + " to " +
                            std::to_string(t.rows.end - 1) + " of a " + std::to_string(width) +
                            "x" + std::to_string(height) + " image");
    if (e.image.names() != first.exr.image.names())
        throwInputError((t.dir / "oracle.exr").string(), "channels",
                        "differ from " + (first.dir / "oracle.exr").string());
}

// The bands in index order: each exactly once, all of them.
std::vector<Tile> readTiles(const std::vector<std::string>& dirs) {
    std::vector<Tile> tiles;
    for (const std::string& d : dirs) {
        tiles.push_back(readTile(d));
        checkBelongs(tiles.front(), tiles.back());
    }
    std::sort(tiles.begin(), tiles.end(),
              [](const Tile& a, const Tile& b) { return a.spec.index < b.spec.index; });
    const int count = tiles.front().spec.count;
    for (size_t i = 1; i < tiles.size(); ++i)
        if (tiles[i].spec.index == tiles[i - 1].spec.index)
            throwInputError(tiles[i].jsonPath, "tile.index",
                            "band " + std::to_string(tiles[i].spec.index) + " is also in " +
                                tiles[i - 1].dir.string());
    for (int i = 0; i < count; ++i)
        if (size_t(i) >= tiles.size() || tiles[size_t(i)].spec.index != i)
            throwInputError(tiles.front().jsonPath, "tile.count",
                            std::to_string(count) + " bands, but band " + std::to_string(i) +
                                " is not among the " + std::to_string(tiles.size()) +
                                " folders given");
    return tiles;
}

// The bands' rows, one above the other, channels in the bands' order.
ChannelImage joinImages(const std::vector<Tile>& tiles, int width, int height) {
    ChannelImage image(width, height);
    for (const std::string& name : tiles.front().exr.image.names()) {
        float* dst = image.addChannel(name);
        for (const Tile& t : tiles)
            std::memcpy(dst + size_t(t.rows.begin) * size_t(width), t.exr.image.channel(name),
                        t.exr.image.pixelCount() * sizeof(float));
    }
    return image;
}

// Per light, the band's pixels of a sampled light with 0 < V < 1 (TileStats::penumbraPixels).
TileStats tileStats(const Tile& t) {
    TileStats s{oracleStatsFromJson(t.j, t.jsonPath), {}};
    for (const OracleLightStats& l : s.stats.lights) {
        uint64_t n = 0;
        const std::string vName = channels::lightChannel(l.name, channels::kVisibility);
        if (l.area && t.exr.image.has(vName)) {
            const float* V = t.exr.image.channel(vName);
            for (size_t i = 0; i < t.exr.image.pixelCount(); ++i) n += V[i] > 0.0f && V[i] < 1.0f;
        }
        s.penumbraPixels.push_back(n);
    }
    return s;
}

// uniformSpp needs every pixel's variance against the whole image's worst half-width: from the
// stderr and spp channels (the whole run uses the unrounded variance; docs/oracle.md, "Tiles").
void recomputeUniformSpp(const ChannelImage& image, OracleStats& stats) {
    for (OracleLightStats& l : stats.lights) {
        if (!l.area || !(l.area->worstHalfWidth > 0.0)) continue;
        const float* se = image.channel(channels::lightChannel(l.name, channels::kStdErr));
        const float* spp = image.channel(channels::lightChannel(l.name, channels::kSpp));
        double uniform = 0.0;
        for (size_t i = 0; i < image.pixelCount(); ++i) {
            const float v = float(double(se[i]) * double(se[i]) * double(spp[i]));
            uniform = std::max(uniform, uniformSppFor(v, l.area->worstHalfWidth));
        }
        l.area->uniformSpp = uniform;
    }
}

// oracle.json of the whole image: the first band's, without "tile", with the merged stats.
json mergedJson(const std::vector<Tile>& tiles, const OracleStats& stats, double writeSeconds) {
    json j = tiles.front().j;
    j.erase("tile");
    double load = 0.0, write = writeSeconds;
    json folders = json::array();
    for (const Tile& t : tiles) {
        load += t.j["phases_seconds"].value("load", 0.0);
        write += t.j["phases_seconds"].value("write", 0.0);
        folders.push_back(t.dir.string());
    }
    j.update(toJson(stats));
    j["phases_seconds"]["load"] = load;
    j["phases_seconds"]["write"] = write;
    // One process's parts and wall time; the bands ran as separate processes.
    for (const char* key : {"write_exr", "write_previews", "process"})
        j["phases_seconds"].erase(key);
    j["libraries"]["tbb"] = j["tbb"]["version"];
    // The merge writes previews even where the bands had none (trace --no-previews: null).
    j["libraries"]["png"] = pngLibraryVersion();
    j.erase("tbb");
    j["merged_tiles"] = {{"count", tiles.size()}, {"folders", folders}};
    return j;
}

}  // namespace

TraceMergeFiles mergeTraceTiles(const std::vector<std::string>& tileDirs,
                                const std::function<fs::path()>& makeOut,
                                const ProgressCallback& progress) {
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    const std::vector<Tile> tiles = readTiles(tileDirs);
    const Tile& first = tiles.front();
    const int width = intAt(first.j, first.jsonPath, "/image/width");
    const int height = intAt(first.j, first.jsonPath, "/image/height");
    std::vector<TileStats> bandStats;
    for (const Tile& t : tiles) bandStats.push_back(tileStats(t));
    OracleStats stats = mergeTileStats(bandStats, width, height);
    const ChannelImage image = joinImages(tiles, width, height);
    recomputeUniformSpp(image, stats);

    const fs::path out = makeOut();
    TraceMergeFiles files;
    files.tiles = tiles.size();
    files.width = width;
    files.height = height;
    files.exr = out / "oracle.exr";
    {
        // The bands' attributes less the tile's own: the whole run's header.
        ExrAttributes attributes;
        for (const auto& a : first.exr.attributes)
            if (a.first != kTileAttribute) attributes.push_back(a);
        Progress writing("writing " + files.exr.string(), image.pixelCount(), progress);
        writeExr(files.exr.string(), image, attributes, int(std::thread::hardware_concurrency()),
                 &writing);
    }
    std::vector<Light> lights;
    for (const OracleLightStats& l : stats.lights) lights.push_back(Light{l.name, l.type});
    files.previews = writePreviews(out, image, lights);
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    files.json = out / "oracle.json";
    writeJsonFile(files.json, mergedJson(tiles, stats, seconds));
    return files;
}

}  // namespace so
