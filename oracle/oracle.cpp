#include "oracle/oracle.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <thread>

#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>
#include <tbb/version.h>

#include "core/camera.h"
#include "core/channels.h"
#include "core/error.h"
#include "core/progress.h"
#include "oracle/accel.h"
#include "oracle/area_light.h"
#include "oracle/hard_shadow.h"
#include "oracle/surface_buffer.h"

namespace so {

namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

void fillGeometryChannels(const SurfaceBuffer& sb, const Accel& accel, ChannelImage& img) {
    namespace ch = channels;
    float* A = img.addChannel(ch::kHit);
    float* P[3] = {img.addChannel(ch::kPX), img.addChannel(ch::kPY), img.addChannel(ch::kPZ)};
    float* N[3] = {img.addChannel(ch::kNX), img.addChannel(ch::kNY), img.addChannel(ch::kNZ)};
    float* Z = img.addChannel(ch::kDepth, std::numeric_limits<float>::infinity());
    float* mesh = img.addChannel(ch::kMeshId, -1.0f);
    float* prim = img.addChannel(ch::kPrimId, -1.0f);
    const LocalFrame& frame = accel.frame();
    for (size_t s = 0; s < sb.slotCount(); ++s) {
        const size_t i = sb.pixelOfSlot(s);
        if (i == SIZE_MAX || !sb.hit[s]) continue;
        A[i] = 1.0f;
        const glm::dvec3 ws = frame.wsFromLs(glm::dvec3(sb.lsPoint(s)));
        for (int k = 0; k < 3; ++k) {
            P[k][i] = float(ws[k]);
            N[k][i] = sb.lsNormal(s)[k];
        }
        Z[i] = sb.wsDepth[s];
        // Exact in float: the loader caps meshes and triangles per mesh at 2^24.
        mesh[i] = float(sb.meshId[s]);
        prim[i] = float(sb.primId[s]);
    }
}

nlohmann::json offsetPolicyJson(OffsetPolicy policy, const LocalFrame& frame,
                                const SurfaceBuffer& sb, double sceneExtent) {
    const double blind = frame.wsLength(sb.lsMaxOffset);
    // The multiple is read off the constant, so the text cannot drift from the code.
    const std::string method =
        policy == OffsetPolicy::ErrorBound
            ? "error bound: the hit point rebuilt in double on the double triangle, the origin "
              "moved " +
                  std::to_string(int(std::ldexp(kLsOriginOffset, 24))) +
                  " * 2^-24 along the geometric normal in the recentred frame scaled by "
                  "2^-exponent, and the triangle the ray leaves from skipped by an Embree filter"
            : "legacy: Waechter-Binder integer-ulp offset, 256 ulp along the geometric normal "
              "(test only)";
    return {{"method", method},
            {"skips_origin_triangle", true},
            {"max_blind_distance", blind},
            {"max_blind_distance_relative", sceneExtent > 0 ? blind / sceneExtent : 0.0},
            {"note",
             "the shadow ray starts this far from the surface along the normal: an occluder that "
             "comes closer to the ray than that, at the surface or anywhere along it, may be "
             "missed; rays to a light stop a margin of 256 ulp of the light's coordinates short of "
             "it"}};
}

}  // namespace

constexpr size_t kVerifyMaxTriangles = size_t(1) << 25;  // about 7 GB for the reference

CameraDesc effectiveCamera(const Scene& scene, const OracleOptions& options) {
    CameraDesc desc = scene.camera;
    if (options.width > 0) desc.width = options.width;
    if (options.height > 0) desc.height = options.height;
    return desc;
}

OracleResult runOracle(const Scene& scene, const OracleOptions& options) {
    const int threads =
        options.threads > 0 ? options.threads : int(std::thread::hardware_concurrency());
    const CameraDesc camDesc = effectiveCamera(scene, options);
    const Camera camera(camDesc);
    nlohmann::json phases = nlohmann::json::object();

    // The BVH is built with a fixed configuration whatever --threads says, so that the same scene
    // always gives the same tree and therefore the same closest hit on exact ties.
    auto t0 = Clock::now();
    EmbreeDevice device("threads=0");
    std::unique_ptr<Accel> accel;
    accel = std::make_unique<Accel>(scene, device);
    phases["build_bvh"] = secondsSince(t0);

    // Tracing uses exactly the requested number of threads, even above the core count (the
    // determinism tests oversubscribe on purpose); TBB would otherwise cap the arena and warn.
    tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, size_t(threads));
    tbb::task_arena arena(threads);

    OracleResult result;
    result.image = ChannelImage(camera.width(), camera.height());
    const uint64_t pixels = uint64_t(camera.width()) * uint64_t(camera.height());

    t0 = Clock::now();
    SurfaceBuffer sb;
    {
        Progress progress("primary rays", pixels, options.progress);
        arena.execute([&] { sb = tracePrimary(*accel, camera, &progress, options.offsetPolicy); });
    }
    phases["primary"] = secondsSince(t0);
    fillGeometryChannels(sb, *accel, result.image);

    // The independent re-trace, built once for all lights (verify.h).
    std::unique_ptr<Verifier> verifier;
    double verifyBuildSeconds = 0.0;
    if (options.verify.pixels > 0) {
        // The reference keeps about 200 bytes per triangle (triangles, nodes, the double
        // vertices): refuse rather than exhaust memory on a huge scene.
        if (scene.stats.triangles > kVerifyMaxTriangles)
            throwInputError(scene.path.string(), "--verify",
                            "the scene has " + std::to_string(scene.stats.triangles) +
                                " triangles; the exact re-trace handles at most " +
                                std::to_string(kVerifyMaxTriangles));
        t0 = Clock::now();
        verifier = std::make_unique<Verifier>(scene, accel->frame(), camera, options.verify,
                                              options.area.seed);
        verifyBuildSeconds = secondsSince(t0);
    }

    nlohmann::json lights = nlohmann::json::array();
    double shadowSeconds = 0.0;
    uint64_t shadowRays = 0;
    const bool penumbra = scene.hasEffect("penumbra");
    const bool contact = scene.hasEffect("contact");
    uint64_t closestHitQueries = 0;
    for (size_t li = 0; li < scene.lights.size(); ++li) {
        const Light& light = scene.lights[li];
        namespace ch = channels;
        float* V = result.image.addChannel(ch::lightChannel(light.name, ch::kVisibility));
        float* cosine = result.image.addChannel(ch::lightChannel(light.name, ch::kCosine));
        // Channels exist only for what the scene asks for: no occ_dist without "contact".
        float* occDist =
            contact ? result.image.addChannel(ch::lightChannel(light.name, ch::kOccluderDistance))
                    : nullptr;
        const bool sampled = penumbra && isAreaLight(light.type);
        nlohmann::json lj = {{"name", light.name}, {"type", lightTypeName(light.type)}};
        Progress progress("shadow rays " + light.name, pixels, options.progress);
        if (sampled) {
            float* stderr_ = result.image.addChannel(ch::lightChannel(light.name, ch::kStdErr));
            float* spp = result.image.addChannel(ch::lightChannel(light.name, ch::kSpp));
            const AreaLight al = makeAreaLight(light, accel->frame());
            AreaShadowStats st;
            arena.execute([&] {
                st = traceAreaShadows(*accel, sb, al, options.area, uint32_t(li), V, stderr_, spp,
                                      cosine, &progress);
            });
            shadowSeconds += st.seconds;
            shadowRays += st.raysTraced;
            const double raysPerSample =
                st.samples ? double(st.raysTraced) / double(st.samples) : 0.0;
            const double uniformSamples = st.uniformSppForWorst * double(st.pixelsSampled);
            lj["method"] = options.area.fixedSpp > 0 ? "sampled (penumbra), fixed spp"
                                                     : "sampled (penumbra), adaptive";
            lj["sampling"] = light.type == LightType::Sphere ? "solid angle of the visible cap"
                                                             : "uniform by area";
            lj["rays_traced"] = st.raysTraced;
            lj["rays_occluded"] = st.raysOccluded;
            lj["rays_skipped"] = {{"background", st.skippedBackground},
                                  {"below_horizon", st.skippedBelowHorizon},
                                  {"behind_light", st.skippedBehindLight},
                                  {"inside_light", st.skippedInsideLight}};
            lj["samples"] = st.samples;
            lj["samples_without_ray"] = st.samples - st.raysTraced;
            lj["pixels_sampled"] = st.pixelsSampled;
            lj["pixels_without_usable_samples"] = st.pixelsWithoutUsableSamples;
            lj["spp_mean"] = st.pixelsSampled ? double(st.samples) / double(st.pixelsSampled) : 0.0;
            lj["spp_max"] = st.maxSpp;
            lj["target_error"] = options.area.fixedSpp > 0
                                     ? nlohmann::json(nullptr)
                                     : nlohmann::json(options.area.targetError);
            lj["max_spp"] = options.area.fixedSpp > 0 ? options.area.fixedSpp : options.area.maxSpp;
            lj["share_reached_target"] =
                st.pixelsSampled ? double(st.reachedTarget) / double(st.pixelsSampled) : 1.0;
            lj["worst_half_width"] = st.worstHalfWidth;
            lj["uniform_equivalent"] = {{"spp", st.uniformSppForWorst},
                                        {"samples", uniformSamples},
                                        {"rays", uniformSamples * raysPerSample},
                                        {"note",
                                         "a uniform run reaching the same worst-pixel half-width "
                                         "(estimated from each pixel's variance)"}};
            lj["sampling_efficiency"] = st.samplingEfficiency;
            lj["seconds"] = st.seconds;
            lj["rays_per_second"] = st.seconds > 0 ? double(st.raysTraced) / st.seconds : 0.0;
        }
        // Hard lights, area lights without "penumbra" (a point at the centre), and the contact
        // rays of sampled area lights (to the centre) all go through the hard-shadow pass.
        if (!sampled || contact) {
            std::vector<float> scratch;
            float* hardV = V;
            float* hardCos = cosine;
            if (sampled) {  // only the occluder distance is wanted
                scratch.assign(2 * size_t(pixels), 0.0f);
                hardV = scratch.data();
                hardCos = scratch.data() + pixels;
            }
            const HardLight hl = makeHardLight(light, accel->frame());
            HardShadowStats st;
            arena.execute([&] {
                st = traceHardShadows(*accel, sb, hl, hardV, hardCos, occDist,
                                      sampled ? nullptr : &progress);
            });
            shadowSeconds += st.seconds;
            shadowRays += st.traced;
            closestHitQueries += st.closestHitQueries;
            nlohmann::json skipped = {{"background", st.skippedBackground},
                                      {"attached", st.skippedAttached}};
            if (light.type == LightType::Spot) skipped["outside_cone"] = st.skippedOutsideCone;
            if (hl.oneSided) skipped["behind_light"] = st.skippedBehindLight;
            nlohmann::json hard = {
                {"rays_traced", st.traced},
                {"rays_occluded", st.occluded},
                {"rays_skipped", skipped},
                {"closest_hit_queries", st.closestHitQueries},
                {"seconds", st.seconds},
                {"rays_per_second", st.seconds > 0 ? double(st.traced) / st.seconds : 0.0}};
            if (sampled) {
                lj["contact_rays"] = hard;
            } else {
                lj["method"] =
                    isAreaLight(light.type)
                        ? "point at the centre (no \"penumbra\" effect): one shadow ray per pixel"
                        : "hard: one shadow ray per pixel";
                lj.update(hard);
            }
        }
        lights.push_back(lj);
        if (verifier) {
            const float* stderr_ =
                sampled ? result.image.channel(ch::lightChannel(light.name, ch::kStdErr)) : nullptr;
            const float* spp =
                sampled ? result.image.channel(ch::lightChannel(light.name, ch::kSpp)) : nullptr;
            arena.execute([&] {
                result.verification.push_back(
                    verifier->verifyLight(light, uint32_t(li), sampled, sb, V, stderr_, spp));
            });
        }
    }
    phases["shadow"] = shadowSeconds;

    const LocalFrame& frame = accel->frame();
    const double sceneExtent = scene.wsBounds.extent();
    result.stats = {
        {"image", {{"width", camera.width()}, {"height", camera.height()}}},
        {"threads", threads},
        {"phases_seconds", phases},
        {"shadow_rays", shadowRays},
        {"closest_hit_queries", closestHitQueries},
        {"effects", scene.effects},
        {"seed", options.area.seed},
        {"shadow_rays_per_second", shadowSeconds > 0 ? double(shadowRays) / shadowSeconds : 0.0},
        {"lights", lights},
        {"frame",
         {{"ws_center", {frame.wsCenter.x, frame.wsCenter.y, frame.wsCenter.z}},
          {"scale_exponent", frame.exponent}}},
        {"offset_policy", offsetPolicyJson(options.offsetPolicy, frame, sb, sceneExtent)},
        {"embree",
         {{"version", EmbreeDevice::version()},
          {"scene_flags", "robust"},
          {"build_quality", "high"}}},
        {"tbb",
         {{"version",
           std::to_string(TBB_VERSION_MAJOR) + "." + std::to_string(TBB_VERSION_MINOR)}}},
    };
    if (verifier) {
        result.stats["verify"] = verificationJson(result.verification, options.verify,
                                                  accel->frame(), verifyBuildSeconds);
        double verifySeconds = verifyBuildSeconds;
        for (const LightVerification& l : result.verification) verifySeconds += l.seconds;
        result.stats["phases_seconds"]["verify"] = verifySeconds;
    }
    return result;
}

}  // namespace so
