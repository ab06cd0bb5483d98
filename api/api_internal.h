// What the public API's types hold inside (include/shadow_oracle/shadow_oracle.h), and the
// translation of the libraries' exceptions into the API's.
#pragma once

#include <optional>
#include <utility>

#include "core/compare_option_table.h"
#include "core/error.h"
#include "core/image.h"
#include "core/progress.h"
#include "core/scene.h"
#include "oracle/oracle_cache.h"
#include "oracle/trace_output.h"
#include "raster_compare/gl/render/renderer.h"
#include "raster_compare/pipeline/comparison.h"
#include "shadow_oracle/shadow_oracle.h"

namespace shadow_oracle {

struct Scene::Data {
    so::Scene scene;
    double loadSeconds = 0.0;  // oracle.json's phases_seconds.load (writeTraceOutput)
    // Scene::atFrame's pose: oracle.json's sequence_frame (writeTraceOutput).
    std::optional<so::SequenceFrame> frame;
};

struct TraceResult::Data {
    so::CachedOracle oracle;  // the image again (compare's input) and the typed stats
    // What oracle.json says beyond the stats (writeTraceOutput): the options traced with (their
    // progress callback dropped) and, at a G-buffer's points, what was done with them.
    so::OracleOptions options;
    std::optional<so::OraclePointsStats> points;
};

struct RenderResult::Data {
    std::string technique;   // raster.exr's technique attribute
    so::ChannelImage image;  // raster.exr, as rendered (the result's image may be moved from)
    so::RasterStats stats;   // raster.json
};

struct CompareResult::Data {
    so::Comparison comparison;  // the rows as the library made them
    int boundaryRadius = so::kDefaultBoundaryRadius;
};

namespace detail {

Image toApi(so::ChannelImage&& image);
so::ChannelImage fromApi(const Image& image);
so::ProgressCallback toLibrary(const ProgressCallback& callback);
// The GL path's options from the API's, checked as the command line's parser checks them.
// The API's render options, checked by the option tables' rows (errors name `file`).
so::RasterOptions rasterOptions(int width, int height, int frames, int warmup,
                                const std::string& file);

// Runs f; the libraries' exceptions come out as the API's, with the same one-line messages.
template <typename F>
auto translated(F&& f) -> decltype(f()) {
    try {
        return f();
    } catch (const so::Cancelled&) {
        throw Cancelled();
    } catch (const Error&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(e.what());
    }
}

}  // namespace detail
}  // namespace shadow_oracle
