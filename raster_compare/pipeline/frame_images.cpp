#include "raster_compare/pipeline/frame_images.h"

namespace so {

FrameImages renderFrameImages(const Scene& scene, const std::vector<const Technique*>& techniques,
                              const OracleOptions& oracle, const OracleCacheOptions& cache,
                              RasterOptions raster, const GlContext& gl,
                              std::vector<std::string>& warnings) {
    FrameImages frame;
    frame.camera = effectiveCamera(scene, oracle);
    CachedOracle traced = traceOrLoad(scene, oracle, cache);
    frame.oracle = std::move(traced.image);
    for (std::string& w : traced.warnings) warnings.push_back(std::move(w));
    raster.frames = 1;
    raster.warmup = 0;
    raster.countWork = false;  // V only: the work is counted by the ordinary comparison
    frame.rasters.resize(techniques.size());
    renderInterleaved(scene, techniques, raster, gl, {nullptr, [&](size_t i, RasterResult&& r) {
                                                          frame.rasters[i] = std::move(r.image);
                                                      }});
    return frame;
}

}  // namespace so
