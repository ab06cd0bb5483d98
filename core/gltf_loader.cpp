// Safe glTF 2.0 loading on top of tinygltf 2.7 (its known holes:
// tests/data/broken_gltf/expected.tsv).
//
// PUBLIC CONTRACT: traversal order and mesh numbering. Mesh ids in the output images (id.mesh)
// are indices into GltfContent::meshes, so this order must never change silently:
//   * The scene drawn is `scene` if the file sets it, else scenes[0]; a file without scenes draws
//     every root node (a node that is no node's child) in index order.
//   * Nodes are visited depth-first, pre-order, children in the order listed. A node reachable
//     along several paths (instancing) is visited once per path.
//   * World transform = wsFromFile * parent chain * node local, in double; the local transform is
//     `matrix` if given, else T * R * S (the quaternion is normalised).
//   * For each visited node with a mesh, each primitive of that mesh, in order, becomes one
//     MeshPrimitive named "FILE#<node name or nodeN>/<mesh name or meshM>/primK". Triangle lists
//     are kept as is; strips become (i, i+1, i+2) with odd i swapped to (i+1, i, i+2), fans become
//     (0, i+1, i+2). Point and line primitives, and primitives with no triangle, produce no
//     MeshPrimitive (and so no id): they are counted in skippedPrimitives with a warning.
//   * The camera is the first node in that order with a `camera` (if that camera is orthographic,
//     there is no camera, with a warning); lights (KHR_lights_punctual) are listed in that order,
//     one per visit of a node that has one, named after the light and made unique ("_2", "_3"...).
//
// Safety: everything tinygltf would read or we will read is checked first, partly on the raw JSON
// before tinygltf sees it (URIs, GLB chunks, nesting depth, integer ranges, image bufferViews)
// because tinygltf 2.7 either reports those problems vaguely or reads out of bounds on them.
//
// What each part reads: gltf_json_checks / gltf_buffers / gltf_lights check the raw JSON,
// gltf_glb the GLB container, gltf_parse runs tinygltf, gltf_meshopt / gltf_draco decode the
// compressed data, gltf_nodes walks the node graph, gltf_camera and gltf_lights read what nodes
// carry, gltf_primitives plans and builds the meshes, gltf_alpha their alpha-tested materials,
// gltf_animation_load a sequence's animations.
#include "core/gltf_loader.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <set>

#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/gltf_alpha.h"
#include "core/gltf_animation_load.h"
#include "core/gltf_buffers.h"
#include "core/gltf_camera.h"
#include "core/gltf_detail.h"
#include "core/gltf_draco.h"
#include "core/gltf_extensions.h"
#include "core/gltf_glb.h"
#include "core/gltf_json_checks.h"
#include "core/gltf_lights.h"
#include "core/gltf_meshopt.h"
#include "core/gltf_nodes.h"
#include "core/gltf_parse.h"
#include "core/gltf_primitives.h"

namespace so {
namespace {

using namespace gltf_detail;

void convert(Context& ctx, const tinygltf::Model& model, const Json& doc,
             const glm::dmat4& wsFromFile) {
    GltfContent& out = *ctx.out;
    checkBufferViews(ctx, model);
    checkNodeIndices(ctx, model);
    checkNodeGraph(ctx, model);
    readAnimations(ctx, model, doc);
    std::vector<ChainLink> links;
    std::vector<std::shared_ptr<const AnimatedNode>> stillNodes(model.nodes.size());
    const bool anyMoving = std::any_of(ctx.animatedNodes.begin(), ctx.animatedNodes.end(),
                                       [](const auto& n) { return n != nullptr; });

    // Pass 1: validate and count everything, so that limits are checked before allocating.
    std::vector<PlannedPrimitive> plan;
    PlanCounts counts;
    bool cameraSeen = false;
    std::set<std::string> lightNames;
    traverse(ctx, model, doc, wsFromFile, anyMoving ? &links : nullptr, [&](const Instance& inst) {
        const tinygltf::Node& node = model.nodes[inst.node];
        addCamera(ctx, model, inst, out.camera, cameraSeen);
        addLight(ctx, model, inst, lightNames);
        if (node.mesh < 0) return;
        counts.skinsOrMorphs |= node.skin >= 0 || !node.weights.empty();
        const size_t primitives = model.meshes[size_t(node.mesh)].primitives.size();
        std::shared_ptr<MeshAnimation> animation =
            anyMoving ? meshAnimation(ctx, model, links, inst, wsFromFile, stillNodes) : nullptr;
        for (size_t k = 0; k < primitives; ++k)
            if (std::optional<PlannedPrimitive> pp =
                    planPrimitive(ctx, model, doc, inst, k, counts)) {
                pp->animation = animation;
                addToPlan(ctx, *pp, plan, counts);
            }
    });
    planWarnings(counts, out);

    // Pass 2: build.
    GltfAlpha alpha(ctx, model, doc);
    out.meshes.reserve(plan.size());
    for (const PlannedPrimitive& pp : plan)
        out.meshes.push_back(buildPrimitive(ctx, model, doc, pp, alpha));
    out.alphaTextures = alpha.takeTextures();
    alphaWarnings(alpha, model, out);
}

}  // namespace

GltfContent loadGltf(const std::filesystem::path& path, const std::string& displayName,
                     const glm::dmat4& wsFromFile, const LoadLimits& limits, bool readAlphaTextures,
                     const Sequence* sequence) {
    GltfContent content;
    Context ctx;
    ctx.playAnimations = sequence != nullptr;
    if (sequence) ctx.animationClip = sequence->animation;
    ctx.displayName = displayName;
    ctx.limits = limits;
    ctx.readAlphaTextures = readAlphaTextures;
    ctx.out = &content;
    std::error_code ec;
    fs::path folder = fs::absolute(path, ec).lexically_normal().parent_path();
    if (ec) fail(ctx, "", "cannot resolve the path");
    ctx.folderPrefix = folder.string();
    if (ctx.folderPrefix.empty() || ctx.folderPrefix.back() != '/') ctx.folderPrefix += '/';
    ctx.canonicalFolder = fs::weakly_canonical(folder, ec);
    if (ec) fail(ctx, "", "cannot resolve the folder");

    std::vector<unsigned char> data;
    std::string err = readCapped(ctx, path, data);
    if (!err.empty()) fail(ctx, "", err);
    if (data.empty()) fail(ctx, "", "file is empty");
    if (data.size() > std::numeric_limits<uint32_t>::max())
        fail(ctx, "", "file is 4 GiB or more (tinygltf limit)");

    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    const bool glb = data.size() >= 4 && std::memcmp(data.data(), "glTF", 4) == 0;
    if (ext == ".glb" && !glb) fail(ctx, "GLB header", "bad magic (not a binary glTF file)");

    GlbChunks chunks{data.data(), data.size(), std::nullopt};
    if (glb) chunks = glbChunks(ctx, data);
    const unsigned char* json = chunks.json;
    const size_t jsonSize = chunks.jsonSize;

    checkJsonDepth(ctx, json, jsonSize);
    Json doc;
    try {
        doc = Json::parse(json, json + jsonSize);
    } catch (const Json::exception& e) {
        fail(ctx, "", "invalid JSON: " + printable(e.what(), 200));
    }
    if (!doc.is_object()) fail(ctx, "", "not a glTF file (the JSON is not an object)");
    checkNumbers(ctx, doc, "", "", "");
    checkAssetAndViews(ctx, doc);
    checkBuffers(ctx, doc, glb, chunks.binSize);
    checkImageBufferViews(ctx, doc);
    checkLights(ctx, doc);
    checkPrimitivesParse(ctx, doc);
    const GltfExtensions extensions = checkExtensions(ctx, doc);
    ctx.meshQuantization = extensions.meshQuantization;
    content.gltfExtensionsIgnored = extensions.ignored;

    // Draco and meshopt files hold what tinygltf 2.7 refuses (an indices accessor without a
    // bufferView, a buffer without data): it reads a copy of the JSON with those filled in, and
    // the extensions are decoded from the file's own JSON afterwards.
    Json tinyDoc = doc;
    const bool rewritten = prepareDracoJson(ctx, tinyDoc) | prepareMeshoptJson(tinyDoc);
    if (rewritten) data = rewrittenFile(tinyDoc, glb, chunks, data);
    if (data.size() > std::numeric_limits<uint32_t>::max())
        fail(ctx, "", "file is 4 GiB or more (tinygltf limit)");
    tinyDoc = Json();

    tinygltf::Model model = parseWithTinygltf(ctx, data, glb);
    decodeMeshopt(ctx, model, doc);
    decodeDraco(ctx, model, doc);
    convert(ctx, model, doc, wsFromFile);
    return content;
}

}  // namespace so
