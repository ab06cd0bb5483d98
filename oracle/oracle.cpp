#include "oracle/oracle.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

#include <tbb/info.h>
#include <tbb/task_arena.h>
#include <tbb/version.h>

#include "core/camera.h"
#include "core/channels.h"
#include "core/error.h"
#include "core/geometry_channels.h"
#include "core/progress.h"
#include "oracle/accel.h"
#include "oracle/area_light.h"
#include "oracle/area_shadow.h"
#include "oracle/exact_penumbra.h"
#include "oracle/exact_scene.h"
#include "oracle/hard_shadow.h"
#include "oracle/lights/area_light_kind.h"
#include "oracle/mesh_facing.h"
#include "oracle/penumbra_choice.h"
#include "oracle/points.h"
#include "oracle/primary_image.h"
#include "oracle/surface_buffer.h"
#include "oracle/thread_arena.h"

namespace so {

namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

OracleOffsetStats offsetPolicyStats(OffsetPolicy policy, const LocalFrame& frame,
                                    const SurfaceBuffer& sb, double sceneExtent) {
    OracleOffsetStats o;
    // The multiple is read off the constant, so the text cannot drift from the code.
    o.method =
        policy == OffsetPolicy::ErrorBound
            ? "error bound: the hit point rebuilt in double on the double triangle, the origin "
              "moved " +
                  std::to_string(int(std::ldexp(kLsOriginOffset, 24))) +
                  " * 2^-24 along the geometric normal in the recentred frame scaled by "
                  "2^-exponent, and the triangle the ray leaves from skipped by an Embree filter "
                  "wherever Embree's rounding could report it (rays within its tangency bound)"
            : "legacy: Waechter-Binder integer-ulp offset, 256 ulp along the geometric normal "
              "(test only)";
    o.skipsOriginTriangle = true;
    o.maxBlindDistance = frame.wsLength(sb.lsMaxOffset);
    o.maxBlindDistanceRelative = sceneExtent > 0 ? o.maxBlindDistance / sceneExtent : 0.0;
    return o;
}

// What the passes over the lights share.
struct LightPass {
    const Scene& scene;
    const OracleOptions& options;
    const Accel& accel;
    const SurfaceBuffer& sb;
    tbb::task_arena& arena;
    ChannelImage& image;
    uint64_t pixels;
    bool penumbra, contact;
    // The exact penumbra pass's scene (--penumbra exact, both or auto, area lights); null
    // otherwise.
    const ExactScene* exact;
    // --penumbra auto: the probe's points (penumbra_choice.h), and the points the camera hit.
    const PenumbraProbe* probe;
    uint64_t hitPoints;
    // The back faces the exact pass may leave out (mesh_facing.h); null without a camera.
    const MeshFacing* facing;
};

// An area light with "penumbra": its V, stderr, spp and cos planes (and unconverged, adaptive).
AreaShadowPlanes sampledPlanes(const LightPass& p, const Light& light, float* V, float* cosine) {
    namespace ch = channels;
    AreaShadowPlanes out{V, p.image.addChannel(ch::lightChannel(light.name, ch::kStdErr)),
                         p.image.addChannel(ch::lightChannel(light.name, ch::kSpp)), cosine,
                         nullptr};
    // Only adaptive runs have a target to miss.
    if (p.options.area.fixedSpp <= 0)
        out.unconverged = p.image.addChannel(ch::lightChannel(light.name, ch::kUnconverged));
    return out;
}

// The sampled pass (on out.onlySlots where given).
AreaShadowStats traceSampledLight(const LightPass& p, uint32_t li, const AreaShadowPlanes& out,
                                  Progress& progress) {
    const AreaLight al = makeAreaLight(p.scene.lights[li], p.accel.frame());
    AreaShadowStats s;
    p.arena.execute(
        [&] { s = traceAreaShadows(p.accel, p.sb, al, p.options.area, li, out, &progress); });
    return s;
}

// Every area light type has an exact pass (oracle/lights/).
bool exactPassTakes(LightType type) {
    return isAreaLight(type);
}

// Why the exact pass does not apply to a light, or "" where it does.
std::string exactNotApplied(const Light& light) {
    if (!exactPassTakes(light.type))
        return std::string(lightTypeName(light.type)) + " light (not an area light)";
    return "";
}

// --penumbra exact on a light the exact pass applies to: the pass finds its own pixels (every
// pixel the camera hit), and the sampled pass runs only on those it cannot answer (too many
// occluders, alpha-tested), so no pixel keeps a sampled 0 or 1 because its samples agreed.
AreaShadowStats traceExactThenSampled(const LightPass& p, uint32_t li, AreaShadowPlanes planes,
                                      Progress& progress) {
    namespace ch = channels;
    const Light& light = p.scene.lights[li];
    ExactPenumbraOptions options = p.options.penumbra;
    options.method = PenumbraMethod::Exact;  // also where auto chose it
    ExactPenumbraPlanes e;
    e.V = planes.V;
    e.stderr_ = planes.stderr_;
    e.cosine = planes.cosine;
    e.exactMask = p.image.addChannel(ch::lightChannel(light.name, ch::kExact));
    if (areaLightKind(light.type).bounded())
        e.bound = p.image.addChannel(ch::lightChannel(light.name, ch::kBound));
    std::vector<uint8_t> needsSampling;
    e.needsSampling = &needsSampling;
    ExactPenumbraStats st;
    {
        Progress exactProgress("exact penumbra " + light.name, p.sb.slotCount(),
                               p.options.progress);
        p.arena.execute([&] {
            st = exactPenumbraPass(*p.exact, p.sb, makeAreaLight(light, p.accel.frame()), options,
                                   e, &exactProgress, p.facing);
        });
    }
    planes.onlySlots = &needsSampling;
    AreaShadowStats s = traceSampledLight(p, li, planes, progress);
    s.exact = std::move(st);
    return s;
}

// --penumbra auto: the method for one light (penumbra_choice.h).
PenumbraChoice choosePenumbra(const LightPass& p, uint32_t li) {
    const Light& light = p.scene.lights[li];
    PenumbraChoice c;
    if (!p.probe) {  // no light the exact pass applies to
        c.reason = "the exact pass does not apply: " + exactNotApplied(light);
        return c;
    }
    p.arena.execute([&] {
        c = choosePenumbraMethod(p.accel, p.exact, *p.probe, makeAreaLight(light, p.accel.frame()),
                                 li, p.options.area, p.options.penumbra, p.hitPoints,
                                 exactNotApplied(light));
    });
    return c;
}

// --penumbra both (or exact on a light the pass does not apply to), after the sampled pass:
// NAME.exact (and NAME.V_exact with both), V and stderr replaced with exact where it applies.
ExactPenumbraStats traceExactPenumbra(const LightPass& p, uint32_t li, float* V) {
    namespace ch = channels;
    const Light& light = p.scene.lights[li];
    const ExactPenumbraOptions& options = p.options.penumbra;
    ExactPenumbraPlanes planes;
    planes.V = V;
    planes.stderr_ = p.image.channel(ch::lightChannel(light.name, ch::kStdErr));
    planes.spp = p.image.channel(ch::lightChannel(light.name, ch::kSpp));
    planes.exactMask = p.image.addChannel(ch::lightChannel(light.name, ch::kExact));
    if (options.method == PenumbraMethod::Both)
        planes.Vexact = p.image.addChannel(ch::lightChannel(light.name, ch::kVisibilityExact));
    if (areaLightKind(light.type).bounded())
        planes.bound = p.image.addChannel(ch::lightChannel(light.name, ch::kBound));
    ExactPenumbraStats st;
    st.method = options.method;
    st.allPixels = options.allPixels;
    st.notApplied = exactNotApplied(light);
    if (!st.notApplied.empty()) {
        // Every pixel sampled: the mask stays 0 (a new channel's fill), V_exact is V.
        if (planes.Vexact) std::copy(V, V + p.pixels, planes.Vexact);
        return st;
    }
    Progress progress("exact penumbra " + light.name, p.sb.slotCount(), p.options.progress);
    p.arena.execute([&] {
        st = exactPenumbraPass(*p.exact, p.sb, makeAreaLight(light, p.accel.frame()), options,
                               planes, &progress, p.facing);
    });
    return st;
}

// One shadow ray per pixel to a point: hard lights, area lights without "penumbra" (to the
// centre), and the contact rays of sampled area lights (to the centre; then only occDist is kept).
HardShadowStats traceHardLight(const LightPass& p, uint32_t li, bool sampled, float* V,
                               float* cosine, float* occDist, Progress& progress) {
    const Light& light = p.scene.lights[li];
    std::vector<float> scratch;
    if (sampled) {  // only the occluder distance is wanted
        scratch.assign(2 * size_t(p.pixels), 0.0f);
        V = scratch.data();
        cosine = scratch.data() + p.pixels;
    }
    const HardLight hl = makeHardLight(light, p.accel.frame());
    HardShadowStats s;
    p.arena.execute([&] {
        s = traceHardShadows(p.accel, p.sb, hl, {V, cosine, occDist},
                             sampled ? nullptr : &progress);
    });
    return s;
}

// Adds the light's channels (docs/exr-channels.md) and traces it.
OracleLightStats traceLight(const LightPass& p, uint32_t li) {
    namespace ch = channels;
    const Light& light = p.scene.lights[li];
    float* V = p.image.addChannel(ch::lightChannel(light.name, ch::kVisibility));
    float* cosine = p.image.addChannel(ch::lightChannel(light.name, ch::kCosine));
    // Channels exist only for what the scene asks for: no occ_dist without "contact".
    float* occDist = p.contact
                         ? p.image.addChannel(ch::lightChannel(light.name, ch::kOccluderDistance))
                         : nullptr;
    OracleLightStats l;
    l.name = light.name;
    l.type = light.type;
    const bool sampled = p.penumbra && isAreaLight(light.type);
    Progress progress("shadow rays " + light.name, p.pixels, p.options.progress);
    if (sampled) {
        PenumbraMethod method = p.options.penumbra.method;
        if (method == PenumbraMethod::Auto) {
            l.choice = choosePenumbra(p, li);
            method = l.choice->chosen;
        }
        const AreaShadowPlanes planes = sampledPlanes(p, light, V, cosine);
        const bool exactFirst = method == PenumbraMethod::Exact && exactNotApplied(light).empty();
        if (exactFirst) {
            l.area = traceExactThenSampled(p, li, planes, progress);
        } else {
            l.area = traceSampledLight(p, li, planes, progress);
            if (method != PenumbraMethod::Sampled) l.area->exact = traceExactPenumbra(p, li, V);
        }
        const char* sampling = p.options.area.fixedSpp > 0 ? "fixed spp" : "adaptive";
        l.method = exactFirst ? std::string("exact (every pixel; sampled, ") + sampling +
                                    ", where the exact pass gives no answer)"
                              : std::string("sampled (penumbra), ") + sampling;
    } else {
        l.method = isAreaLight(light.type)
                       ? "point at the centre (no \"penumbra\" effect): one shadow ray per pixel"
                       : "hard: one shadow ray per pixel";
    }
    if (!sampled || p.contact)
        l.hard = traceHardLight(p, li, sampled, V, cosine, occDist, progress);
    return l;
}

// The independent re-trace of one light (verify.h), from the channels just written.
LightVerification verifyLight(const LightPass& p, const Verifier& verifier, uint32_t li,
                              bool sampled) {
    namespace ch = channels;
    const Light& light = p.scene.lights[li];
    const float* V = p.image.channel(ch::lightChannel(light.name, ch::kVisibility));
    const float* stderr_ =
        sampled ? p.image.channel(ch::lightChannel(light.name, ch::kStdErr)) : nullptr;
    const float* spp = sampled ? p.image.channel(ch::lightChannel(light.name, ch::kSpp)) : nullptr;
    // A disk or sphere light whose V the exact pass replaced (--penumbra exact, or auto where it
    // chose exact): V is bounded where NAME.exact is 1. With both, V stays sampled.
    const std::string boundName = ch::lightChannel(light.name, ch::kBound);
    const bool bounded =
        sampled && p.options.penumbra.method != PenumbraMethod::Both && p.image.has(boundName);
    const float* bound = bounded ? p.image.channel(boundName) : nullptr;
    // A pixel the exact pass gave (--penumbra exact) took no samples, yet it is a measurement: the
    // verifier, which reads spp 0 as a pixel skipped below the horizon, is given 1 there, so that
    // it compares the exact V (stderr 0) with its own independent estimate.
    std::vector<float> sppMeasured;
    const std::string exactName = ch::lightChannel(light.name, ch::kExact);
    // With bound: the exact pixels are checked against the polygons' bound as well (verify.h).
    const float* exact = bound && p.image.has(exactName) ? p.image.channel(exactName) : nullptr;
    if (sampled && p.image.has(exactName)) {
        const float* mask = p.image.channel(exactName);
        sppMeasured.assign(spp, spp + p.pixels);
        for (size_t i = 0; i < sppMeasured.size(); ++i)
            if (mask[i] == 1.0f && sppMeasured[i] == 0.0f) sppMeasured[i] = 1.0f;
        spp = sppMeasured.data();
    }
    LightVerification out;
    p.arena.execute([&] {
        out = verifier.verifyLight(light, li, sampled, p.sb, V, stderr_, spp, bound, exact);
    });
    return out;
}

constexpr size_t kVerifyMaxTriangles = size_t(1) << 25;  // about 7 GB for the reference

// The reference for --verify, built once for all lights; null without --verify.
std::unique_ptr<Verifier> makeVerifier(const Scene& scene, const OracleOptions& options,
                                       const LocalFrame& frame, const Camera* camera,
                                       OracleStats& stats) {
    if (options.verify.pixels <= 0) return nullptr;
    // The reference keeps about 200 bytes per triangle (triangles, nodes, the double vertices):
    // refuse rather than exhaust memory on a huge scene.
    if (scene.stats.triangles > kVerifyMaxTriangles)
        throwInputError(scene.path.string(), "verify",
                        "the scene has " + std::to_string(scene.stats.triangles) +
                            " triangles; the exact re-trace handles at most " +
                            std::to_string(kVerifyMaxTriangles));
    const auto t0 = Clock::now();
    VerifyOptions verify = options.verify;
    // The oracle's stated intervals (area_shadow.h), which the verifier's threshold follows.
    verify.oracleDof = options.area.fixedSpp > 0 ? kReplicas - 1 : kAdaptiveDof;
    auto verifier = std::make_unique<Verifier>(scene, frame, camera, verify, options.area.seed);
    OracleVerifyStats& v = stats.verify.emplace();
    v.buildSeconds = secondsSince(t0);
    v.options = options.verify;
    v.wsToleranceAbs = frame.wsLength(Verifier::kTolAbs);
    v.tolerancePerUnitDistance = Verifier::kTolPerT;
    return verifier;
}

// The exact penumbra pass's scene: with --penumbra exact, both or auto, an area light and
// "penumbra".
// Alpha-tested meshes are in it: the pixels whose pyramid holds one keep their sampled V.
std::unique_ptr<ExactScene> makeExactScene(const Scene& scene, const OracleOptions& options,
                                           const LocalFrame& frame) {
    if (options.penumbra.method == PenumbraMethod::Sampled || !scene.hasEffect("penumbra"))
        return nullptr;
    const bool any = std::any_of(scene.lights.begin(), scene.lights.end(),
                                 [](const Light& l) { return exactPassTakes(l.type); });
    return any ? std::make_unique<ExactScene>(scene, frame) : nullptr;
}

// --penumbra auto's probe (penumbra_choice.h): a coarse image of the same view (one pixel in 64),
// whatever band is traced, or at a G-buffer's points one point in 64.
struct ProbeBuffers {
    SurfaceBuffer coarse;
    std::vector<uint8_t> slots;
    PenumbraProbe probe;
};
std::unique_ptr<ProbeBuffers> makeProbe(const Scene& scene, const OracleOptions& options,
                                        const Accel& accel, tbb::task_arena& arena,
                                        const SurfaceBuffer& sb, bool points) {
    auto b = std::make_unique<ProbeBuffers>();
    if (points) {
        b->slots = sparseSlots(sb, 64);
        b->probe = {&sb, &b->slots};
        return b;
    }
    CameraDesc desc = effectiveCamera(scene, options);
    desc.width = std::max(1, (desc.width + 4) / 8);
    desc.height = std::max(1, (desc.height + 4) / 8);
    const Camera coarse(desc);
    arena.execute([&] {
        b->coarse = tracePrimary(accel, coarse, nullptr, options.offsetPolicy);
        buildNearFields(accel, b->coarse);
    });
    b->probe = {&b->coarse, nullptr};
    return b;
}

uint64_t hitPoints(const SurfaceBuffer& sb) {
    uint64_t n = 0;
    for (size_t s = 0; s < sb.slotCount(); ++s) n += sb.pixelOfSlot(s) != SIZE_MAX && sb.hit[s];
    return n;
}

// Every light in scene order, each verified right after it is traced (with --verify).
void traceLights(const LightPass& p, const Verifier* verifier, OracleStats& stats) {
    for (size_t li = 0; li < p.scene.lights.size(); ++li) {
        OracleLightStats l = traceLight(p, uint32_t(li));
        if (l.area) {
            // The exact pass (--penumbra exact or both) is part of the light's shadows too.
            stats.shadowSeconds += l.area->seconds + (l.area->exact ? l.area->exact->seconds : 0.0);
            stats.shadowRays += l.area->raysTraced;
            stats.shadowAlphaTests += l.area->alphaTests;
        }
        if (l.hard) {
            stats.shadowSeconds += l.hard->seconds;
            stats.shadowRays += l.hard->raysTraced;
            stats.closestHitQueries += l.hard->closestHitQueries;
            stats.shadowAlphaTests += l.hard->alphaTests;
        }
        if (verifier)
            stats.verify->lights.push_back(verifyLight(p, *verifier, uint32_t(li), l.sampled()));
        stats.lights.push_back(std::move(l));
    }
}

// The fields of the stats that describe the setup rather than the tracing.
void describeSetup(const Scene& scene, const OracleOptions& options, const Accel& accel,
                   const SurfaceBuffer& sb, OracleStats& stats) {
    stats.effects = scene.effects;
    stats.seed = options.area.seed;
    const LocalFrame& frame = accel.frame();
    stats.frame.wsCenter = frame.wsCenter;
    stats.frame.scaleExponent = frame.exponent;
    stats.offsetPolicy =
        offsetPolicyStats(options.offsetPolicy, frame, sb, scene.wsBounds.extent());
    stats.embree = {EmbreeDevice::version(), "robust", "high"};
    stats.tbbVersion = std::to_string(TBB_VERSION_MAJOR) + "." + std::to_string(TBB_VERSION_MINOR);
}

}  // namespace

int tileRowCount(int height) {
    return (height + SurfaceBuffer::kTile - 1) / SurfaceBuffer::kTile;
}

RowBand tileRows(int height, int index, int count) {
    const int64_t tiles = tileRowCount(height);
    if (!(0 <= index && index < count && count <= tiles))
        throw std::invalid_argument("tileRows: band " + std::to_string(index) + " of " +
                                    std::to_string(count) + " of " + std::to_string(tiles) +
                                    " tile rows (needs 0 <= index < count <= tile rows)");
    // Tile rows [floor(index * tiles / count), floor((index + 1) * tiles / count)): every band
    // gets at least one since count <= tiles.
    const int64_t t0 = int64_t(index) * tiles / count, t1 = int64_t(index + 1) * tiles / count;
    return {int(t0) * SurfaceBuffer::kTile, std::min(height, int(t1) * SurfaceBuffer::kTile)};
}

CameraDesc effectiveCamera(const Scene& scene, const OracleOptions& options) {
    CameraDesc desc = options.camera.value_or(scene.camera);
    if (options.width > 0) desc.width = options.width;
    if (options.height > 0) desc.height = options.height;
    return desc;
}

namespace {

// What runOracle and runOracleAtPoints share: the BVH (built with a fixed configuration whatever
// --threads says, so that the same scene always gives the same tree and therefore the same closest
// hit on exact ties) and the arena with exactly the requested number of threads (thread_arena.h).
struct OracleSetup {
    OracleSetup(const Scene& scene, int threads)
        : device("threads=0"),
          accel(scene, device),
          threadArena(threads),
          arena(threadArena.arena()) {}
    EmbreeDevice device;
    const Accel accel;
    ThreadArena threadArena;
    tbb::task_arena& arena;
};

// options.rows as tileRows makes them: a multiple of the tile height, inside the image, not empty.
void checkRows(const RowBand& rows, int height) {
    if (rows.begin % SurfaceBuffer::kTile != 0 || rows.begin < 0 || rows.begin >= rows.end ||
        rows.end > height)
        throw std::invalid_argument("runOracle: options.rows [" + std::to_string(rows.begin) +
                                    ", " + std::to_string(rows.end) +
                                    ") is not a band of tileRows for an image " +
                                    std::to_string(height) + " rows high");
}

int resolvedThreads(const OracleOptions& options) {
    return options.threads > 0 ? options.threads : int(std::thread::hardware_concurrency());
}

// The shadow passes over every light, on a filled SurfaceBuffer. camera: null in points mode.
void traceShadowPasses(const Scene& scene, const OracleOptions& options, OracleSetup& setup,
                       const SurfaceBuffer& sb, const Camera* camera, OracleResult& result) {
    OracleStats& stats = result.stats;
    const std::unique_ptr<Verifier> verifier =
        makeVerifier(scene, options, setup.accel.frame(), camera, stats);
    const std::unique_ptr<ExactScene> exact = makeExactScene(scene, options, setup.accel.frame());
    std::optional<MeshFacing> facing;
    if (exact && camera && options.penumbra.backFaces)
        facing = meshFacing(*exact, setup.accel.frame().lsFromWs(camera->wsEye()));
    const std::unique_ptr<ProbeBuffers> probe =
        options.penumbra.method == PenumbraMethod::Auto && exact
            ? makeProbe(scene, options, setup.accel, setup.arena, sb, camera == nullptr)
            : nullptr;
    if (probe) {
        probe->probe.facing = facing ? &*facing : nullptr;
        probe->probe.sceneTriangles = scene.stats.triangles;
    }
    const LightPass pass{scene,
                         options,
                         setup.accel,
                         sb,
                         setup.arena,
                         result.image,
                         result.image.pixelCount(),
                         scene.hasEffect("penumbra"),
                         scene.hasEffect("contact"),
                         exact.get(),
                         probe ? &probe->probe : nullptr,
                         hitPoints(sb),
                         facing ? &*facing : nullptr};
    traceLights(pass, verifier.get(), stats);
    describeSetup(scene, options, setup.accel, sb, stats);
    // Embree reports errors from its queries only through the device: one here (none is expected
    // after the build) would mean a result that cannot be trusted.
    setup.device.throwIfError();
}

}  // namespace

OracleResult runOracle(const Scene& scene, const OracleOptions& options) {
    OracleResult result;
    OracleStats& stats = result.stats;
    stats.threads = resolvedThreads(options);
    const Camera camera(effectiveCamera(scene, options));
    stats.width = camera.width();
    stats.height = camera.height();

    // A band (trace --tile) keeps only its rows; every pass indexes pixels within it. Checked
    // before the BVH is built: a caller's bad band fails at once.
    const RowBand rows = options.rows.value_or(RowBand{0, camera.height()});
    checkRows(rows, camera.height());
    if (options.rows && options.verify.pixels > 0)
        throwInputError("options", "rows",
                        "a band of rows cannot be verified (verify the whole image)");

    auto t0 = Clock::now();
    OracleSetup setup(scene, stats.threads);
    stats.buildBvhSeconds = secondsSince(t0);
    const Accel& accel = setup.accel;
    result.image = ChannelImage(camera.width(), rows.count());
    const uint64_t pixels = result.image.pixelCount();

    t0 = Clock::now();
    SurfaceBuffer sb;
    {
        Progress progress("primary rays", pixels, options.progress);
        setup.arena.execute([&] {
            sb = tracePrimary(accel, camera, &progress, options.offsetPolicy, rows.begin, rows.end);
            buildNearFields(accel, sb);
        });
    }
    stats.primarySeconds = secondsSince(t0);
    stats.primaryAlphaTests = sb.alphaTests;
    fillGeometryChannels(sb, accel, result.image);
    traceShadowPasses(scene, options, setup, sb, &camera, result);
    return result;
}

OracleResult runOracleAtPoints(const Scene& scene, const GBuffer& gbuffer,
                               const OracleOptions& options) {
    if (options.width > 0 || options.height > 0)
        throwInputError("options", "width/height",
                        "must be 0 at a G-buffer's points (the image is the G-buffer's size)");
    if (options.rows) throwInputError("options", "rows", "must be empty at a G-buffer's points");
    if (options.camera)
        throw std::invalid_argument(
            "runOracleAtPoints: options.camera must be empty (the G-buffer holds the points)");
    OracleResult result;
    OracleStats& stats = result.stats;
    stats.threads = resolvedThreads(options);
    stats.width = gbuffer.width;
    stats.height = gbuffer.height;

    auto t0 = Clock::now();
    OracleSetup setup(scene, stats.threads);
    stats.buildBvhSeconds = secondsSince(t0);

    t0 = Clock::now();
    PointsSurface ps;
    setup.arena.execute([&] {
        ps = surfaceFromPoints(scene, setup.accel, gbuffer, options.offsetPolicy);
        buildNearFields(setup.accel, ps.sb);
    });
    stats.primarySeconds = secondsSince(t0);
    stats.primaryAlphaTests = ps.sb.alphaTests;
    result.image = ChannelImage(gbuffer.width, gbuffer.height);
    fillGeometryChannels(ps.sb, setup.accel, result.image);
    float* status = result.image.addChannel(channels::kPointsStatus);
    for (size_t i = 0; i < ps.status.size(); ++i) status[i] = float(ps.status[i]);
    traceShadowPasses(scene, options, setup, ps.sb, nullptr, result);
    result.points = std::move(ps.stats);
    return result;
}

}  // namespace so
