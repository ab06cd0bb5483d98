#include "raster_compare/pipeline/frame_images.h"

#include "core/error.h"

namespace so {

FrameImages renderFrameImages(const Scene& scene, const std::vector<const Technique*>& techniques,
                              const OracleOptions& oracle, const OracleCacheOptions& cache,
                              RasterOptions raster, const GlContext& gl,
                              std::vector<std::string>& warnings, const ChannelImage* traced,
                              bool timed) {
    FrameImages frame;
    frame.camera = effectiveCamera(scene, oracle);
    if (traced) {
        SO_CHECK(traced->width() == frame.camera.width && traced->height() == frame.camera.height);
        frame.oracle = *traced;
    } else {
        CachedOracle loaded = traceOrLoad(scene, oracle, cache);
        frame.oracle = std::move(loaded.image);
        for (std::string& w : loaded.warnings) warnings.push_back(std::move(w));
    }
    if (!timed) {
        raster.frames = 1;
        raster.warmup = 0;
        raster.countWork = false;  // V only: the work is counted by the ordinary comparison
    }
    frame.rasters.resize(techniques.size());
    frame.stats.resize(techniques.size());
    renderInterleaved(scene, techniques, raster, gl, {nullptr, [&](size_t i, RasterResult&& r) {
                                                          frame.rasters[i] = std::move(r.image);
                                                          frame.stats[i] = std::move(r.stats);
                                                      }});
    return frame;
}

}  // namespace so
