#include "oracle/primary_image.h"

#include <thread>

#include <tbb/task_arena.h>

#include "core/camera.h"
#include "core/channels.h"
#include "core/geometry_channels.h"
#include "core/progress.h"
#include "embree/embree_handles.h"
#include "oracle/accel.h"
#include "oracle/surface_buffer.h"
#include "oracle/thread_arena.h"

namespace so {

void fillGeometryChannels(const SurfaceBuffer& sb, const Accel& accel, ChannelImage& image) {
    GeometryChannelWriter out(image);
    const LocalFrame& frame = accel.frame();
    for (size_t s = 0; s < sb.slotCount(); ++s) {
        const size_t i = sb.pixelOfSlot(s);
        if (i == SIZE_MAX || !sb.hit[s]) continue;
        out.set(i, frame.wsFromLs(glm::dvec3(sb.lsPoint(s))), sb.lsNormal(s), sb.wsDepth[s],
                float(sb.meshId[s]), float(sb.primId[s]));
    }
}

PrimaryImage tracePrimaryImage(const Scene& scene, const OracleOptions& options) {
    const Camera camera(effectiveCamera(scene, options));
    const int threads =
        options.threads > 0 ? options.threads : int(std::thread::hardware_concurrency());
    // The same BVH configuration as runOracle, so the same hits.
    EmbreeDevice device("threads=0");
    const Accel accel(scene, device);
    ThreadArena threadArena(threads);
    tbb::task_arena& arena = threadArena.arena();
    SurfaceBuffer sb;
    {
        Progress progress("primary rays", uint64_t(camera.width()) * uint64_t(camera.height()),
                          options.progress);
        arena.execute([&] { sb = tracePrimary(accel, camera, &progress, options.offsetPolicy); });
    }
    PrimaryImage result{ChannelImage(camera.width(), camera.height()), {}};
    fillGeometryChannels(sb, accel, result.image);
    float* baryU = result.image.addChannel(channels::kBaryU);
    float* baryV = result.image.addChannel(channels::kBaryV);
    for (size_t s = 0; s < sb.slotCount(); ++s) {
        const size_t i = sb.pixelOfSlot(s);
        if (i == SIZE_MAX || !sb.hit[s]) continue;
        baryU[i] = sb.baryU[s];
        baryV[i] = sb.baryV[s];
        result.lsReceivers.extend(glm::dvec3(sb.lsPoint(s)));
    }
    return result;
}

}  // namespace so
