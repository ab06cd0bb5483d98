#include "core/gltf_nodes.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/gtc/quaternion.hpp>

namespace so::gltf_detail {
namespace {

bool allFinite(const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

bool allFinite(const glm::dmat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

// The scene's root nodes: those of `scene` if the file sets it, else of scenes[0]; without scenes,
// every node that is no node's child, in index order.
std::vector<int> sceneRoots(const Context& ctx, const tinygltf::Model& model, const Json& doc) {
    std::vector<int> roots;
    if (model.scenes.empty()) {
        std::vector<char> isChild(model.nodes.size(), 0);
        for (const auto& n : model.nodes)
            for (int c : n.children) isChild[size_t(c)] = 1;
        for (size_t i = 0; i < model.nodes.size(); ++i)
            if (!isChild[i]) roots.push_back(int(i));
    } else {
        if (member(doc, "scene") && model.defaultScene < 0)
            fail(ctx, "scene", "must be a non-negative integer");
        size_t s = model.defaultScene >= 0 ? size_t(model.defaultScene) : 0;
        if (s >= model.scenes.size())
            fail(ctx, "scene",
                 std::to_string(s) + " out of range (" + std::to_string(model.scenes.size()) +
                     " scenes)");
        roots = model.scenes[s].nodes;
        for (size_t i = 0; i < roots.size(); ++i)
            if (roots[i] < 0 || size_t(roots[i]) >= model.nodes.size())
                fail(ctx, idx("scenes", s) + "." + idx("nodes", i),
                     std::to_string(roots[i]) + " out of range (" +
                         std::to_string(model.nodes.size()) + " nodes)");
    }
    return roots;
}

// Shared subtrees multiply (a chain of nodes each listing the next twice expands to 2^depth
// instances), so the number of node instances is counted first, in topological order with
// saturating sums (the graph has no cycle), and bounded like the number of meshes.
void checkInstanceCount(const Context& ctx, const tinygltf::Model& model,
                        const std::vector<int>& roots) {
    const size_t n = model.nodes.size();
    std::vector<uint64_t> instances(n, 0);
    std::vector<size_t> parents(n, 0);
    for (const auto& node : model.nodes)
        for (int c : node.children) ++parents[size_t(c)];
    for (int r : roots)
        instances[size_t(r)] = std::min<uint64_t>(instances[size_t(r)] + 1, 1ull << 62);
    std::vector<size_t> ready;
    for (size_t i = 0; i < n; ++i)
        if (parents[i] == 0) ready.push_back(i);
    uint64_t total = 0;
    while (!ready.empty()) {
        size_t i = ready.back();
        ready.pop_back();
        total = std::min<uint64_t>(total + instances[i], 1ull << 62);
        for (int c : model.nodes[i].children) {
            instances[size_t(c)] =
                std::min<uint64_t>(instances[size_t(c)] + instances[i], 1ull << 62);
            if (--parents[size_t(c)] == 0) ready.push_back(size_t(c));
        }
    }
    const uint64_t maxInstances = ctx.limits.maxMeshes + n;
    if (total > maxInstances)
        fail(ctx, "nodes",
             "the scene expands to " +
                 (total >= (1ull << 62) ? std::string("over 2^62") : std::to_string(total)) +
                 " node instances, more than " + std::to_string(maxInstances));
}

}  // namespace

glm::dmat4 localTransform(const Context& ctx, const tinygltf::Node& n, size_t i) {
    std::string field = idx("nodes", i);
    auto checkArray = [&](const std::vector<double>& v, size_t want, const char* name) {
        if (v.empty()) return false;
        if (v.size() != want)
            fail(ctx, field + "." + name,
                 "expected " + std::to_string(want) + " numbers, got " + std::to_string(v.size()));
        if (!allFinite(v)) fail(ctx, field + "." + name, "non-finite value");
        return true;
    };
    if (checkArray(n.matrix, 16, "matrix")) {
        glm::dmat4 m(1.0);
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m[c][r] = n.matrix[size_t(c * 4 + r)];
        if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0)
            fail(ctx, field + ".matrix", "not affine (last row must be 0 0 0 1)");
        return m;
    }
    glm::dmat4 t(1.0), r(1.0), s(1.0);
    if (checkArray(n.translation, 3, "translation"))
        t[3] = glm::dvec4(n.translation[0], n.translation[1], n.translation[2], 1.0);
    if (checkArray(n.rotation, 4, "rotation")) {
        glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
        double len = glm::length(q);
        if (!(len > 0.0) || !std::isfinite(len))
            fail(ctx, field + ".rotation", "zero-length quaternion");
        r = glm::mat4_cast(q / len);
    }
    if (checkArray(n.scale, 3, "scale")) {
        s[0][0] = n.scale[0];
        s[1][1] = n.scale[1];
        s[2][2] = n.scale[2];
    }
    return t * r * s;
}

void checkNodeIndices(const Context& ctx, const tinygltf::Model& model) {
    for (size_t i = 0; i < model.nodes.size(); ++i) {
        const tinygltf::Node& n = model.nodes[i];
        if (n.mesh < -1 || n.mesh >= int(model.meshes.size()))
            fail(ctx, idx("nodes", i) + ".mesh",
                 std::to_string(n.mesh) + " out of range (" + std::to_string(model.meshes.size()) +
                     " meshes)");
        if (n.camera < -1 || n.camera >= int(model.cameras.size()))
            fail(ctx, idx("nodes", i) + ".camera",
                 std::to_string(n.camera) + " out of range (" +
                     std::to_string(model.cameras.size()) + " cameras)");
    }
}

void checkNodeGraph(const Context& ctx, const tinygltf::Model& model) {
    const size_t n = model.nodes.size();
    for (size_t i = 0; i < n; ++i)
        for (size_t c = 0; c < model.nodes[i].children.size(); ++c) {
            int child = model.nodes[i].children[c];
            if (child < 0 || size_t(child) >= n)
                fail(ctx, idx("nodes", i) + "." + idx("children", c),
                     std::to_string(child) + " out of range (" + std::to_string(n) + " nodes)");
        }
    enum : char { kNew, kOnPath, kDone };
    std::vector<char> state(n, kNew);
    std::vector<std::pair<size_t, size_t>> stack;  // node, next child
    for (size_t root = 0; root < n; ++root) {
        if (state[root] != kNew) continue;
        stack.push_back({root, 0});
        state[root] = kOnPath;
        while (!stack.empty()) {
            auto& [node, next] = stack.back();
            const auto& children = model.nodes[node].children;
            if (next == children.size()) {
                state[node] = kDone;
                stack.pop_back();
                continue;
            }
            size_t child = size_t(children[next++]);
            if (state[child] == kOnPath)
                fail(ctx, idx("nodes", node) + ".children",
                     "cycle in the node graph (back to " + idx("nodes", child) + ")");
            if (state[child] == kNew) {
                state[child] = kOnPath;
                stack.push_back({child, 0});
            }
        }
    }
}

void traverse(const Context& ctx, const tinygltf::Model& model, const Json& doc,
              const glm::dmat4& wsFromFile, std::vector<ChainLink>* links,
              const std::function<void(const Instance&)>& visit) {
    const std::vector<int> roots = sceneRoots(ctx, model, doc);
    std::vector<glm::dmat4> local(model.nodes.size());
    for (size_t i = 0; i < model.nodes.size(); ++i) {
        local[i] = localTransform(ctx, model.nodes[i], i);
        // An animated node is drawn as the animation poses it at t = 0.
        if (ctx.animates(i)) local[i] = ctx.animatedNodes[i]->localAt(0.0);
    }
    checkInstanceCount(ctx, model, roots);
    struct Item {
        size_t node;
        int depth;
        glm::dmat4 parent;
        int64_t parentLink;
    };
    std::vector<Item> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it)
        stack.push_back({size_t(*it), 1, wsFromFile, -1});
    while (!stack.empty()) {
        Item item = stack.back();
        stack.pop_back();
        std::string field = idx("nodes", item.node);
        if (item.depth > ctx.limits.maxNodeDepth)
            fail(ctx, field,
                 "node hierarchy deeper than " + std::to_string(ctx.limits.maxNodeDepth) +
                     " levels");
        glm::dmat4 world = item.parent * local[item.node];
        if (!allFinite(world)) fail(ctx, field, "world transform is not finite");
        int64_t link = -1;
        if (links) {
            const bool parentMoving =
                item.parentLink >= 0 && (*links)[size_t(item.parentLink)].moving;
            links->push_back({item.node, item.parentLink, parentMoving || ctx.animates(item.node)});
            link = int64_t(links->size() - 1);
        }
        visit(Instance{item.node, world, link});
        const auto& children = model.nodes[item.node].children;
        for (auto it = children.rbegin(); it != children.rend(); ++it)
            stack.push_back({size_t(*it), item.depth + 1, world, link});
    }
}

glm::dvec3 unitDirection(const Context& ctx, const glm::dmat4& m, const glm::dvec3& local,
                         const std::string& field) {
    glm::dvec3 d = glm::dvec3(m * glm::dvec4(local, 0.0));
    double len = glm::length(d);
    if (!(len > 0.0) || !std::isfinite(len))
        fail(ctx, field, "transform collapses a direction to zero");
    return d / len;
}

}  // namespace so::gltf_detail
