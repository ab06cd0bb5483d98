#include "oracle/accel.h"

namespace so {

namespace {

// Rejects a candidate hit on the triangle the ray leaves from: the ray's id holds the origin
// triangle's global index, the context the meshes' first global indices. A context filter, run by
// the queries whose ShadowContext turned it on. Like every filter, called from Embree's C code
// during a query: noexcept (nothing here may throw, and no SO_CHECK belongs here), so that a slip
// ends in std::terminate rather than undefined behaviour.
void skipOriginTriangle(const RTCFilterFunctionNArguments* args) noexcept {
    const auto* ctx = reinterpret_cast<const ShadowContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        const unsigned origin = RTCRayN_id(args->ray, args->N, i);
        const unsigned mesh = RTCHitN_geomID(args->hit, args->N, i);
        const unsigned hit = ctx->meshBase[mesh] + RTCHitN_primID(args->hit, args->N, i);
        if (origin == hit) args->valid[i] = 0;
    }
}

// The oracle's build: robust (watertight along shared edges, which is what a ground truth needs:
// contact lines, closed meshes), high quality (built once, traced many times), degenerate
// triangles dropped. The origin filter is a context filter, run only by the queries that ask for
// it; alpha-tested geometries skip the origin triangle in their own filter.
TriangleSceneOptions oracleBuild(bool originFilter) {
    TriangleSceneOptions o;
    o.robust = true;
    o.contextFilter = originFilter;
    o.quality = RTC_BUILD_QUALITY_HIGH;
    o.dropDegenerates = true;
    o.alphaSkipsOrigin = originFilter;
    return o;
}

}  // namespace

Accel::Accel(const Scene& scene, const EmbreeDevice& device, bool originFilter)
    : frame_(LocalFrame::fit(scene.wsBounds)),
      filters_(originFilter),
      triangles_(scene, frame_, device, oracleBuild(originFilter)) {}

void ShadowContext::originFilter(bool on) {
    rtc.filter = on ? skipOriginTriangle : nullptr;
}

ShadowContext Accel::shadowContext(bool coherent) const {
    ShadowContext c;
    rtcInitIntersectContext(&c.rtc);
    if (coherent) c.rtc.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    c.meshBase = triangles_.meshBase().data();
    return c;
}

RTCRayHit singleRayHit(const glm::vec3& org, const glm::vec3& dir, float tfar) {
    RTCRayHit rh;
    rh.ray.org_x = org.x;
    rh.ray.org_y = org.y;
    rh.ray.org_z = org.z;
    rh.ray.dir_x = dir.x;
    rh.ray.dir_y = dir.y;
    rh.ray.dir_z = dir.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = tfar;
    rh.ray.mask = 0xFFFFFFFFu;  // a zero mask would hit nothing (Embree masks are on)
    rh.ray.time = 0.0f;
    rh.ray.flags = 0;
    rh.ray.id = kNoOriginTriangle;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

}  // namespace so
