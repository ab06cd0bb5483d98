#include "core/gltf_animation_load.h"

#include <algorithm>
#include <cmath>

namespace so::gltf_detail {
namespace {

const char* propertyName(AnimatedProperty p) {
    switch (p) {
        case AnimatedProperty::Translation:
            return "translation";
        case AnimatedProperty::Rotation:
            return "rotation";
        default:
            return "scale";
    }
}

AnimationInterpolation interpolationOf(const Context& ctx, const std::string& how,
                                       const std::string& field) {
    if (how == "LINEAR") return AnimationInterpolation::Linear;
    if (how == "STEP") return AnimationInterpolation::Step;
    if (how == "CUBICSPLINE") return AnimationInterpolation::CubicSpline;
    fail(ctx, field + ".interpolation",
         "unknown interpolation " + quoted(printable(how, 40)) +
             " (valid: LINEAR, STEP, CUBICSPLINE)");
}

// The key times: SCALAR FLOAT, finite, strictly increasing, at most maxAnimationKeys.
std::vector<double> readTimes(const Context& ctx, const tinygltf::Model& model, const Json& doc,
                              int accessor, const std::string& field) {
    const std::string acc = idx("accessors", size_t(std::max(accessor, 0)));
    AccessorData a = checkedAccessor(
        ctx, model, doc, accessor, field + ".input", [&](const tinygltf::Accessor& x) {
            if (x.type != TINYGLTF_TYPE_SCALAR || x.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
                fail(ctx, acc, "an animation's input must be SCALAR FLOAT");
        });
    if (a.count > ctx.limits.maxAnimationKeys)
        fail(ctx, acc + ".count",
             std::to_string(a.count) + " keys, over maxAnimationKeys (" +
                 std::to_string(ctx.limits.maxAnimationKeys) + ")");
    std::vector<double> times(size_t(a.count));
    for (uint64_t i = 0; i < a.count; ++i) {
        times[size_t(i)] = readComponent(a, i, 0);
        if (!std::isfinite(times[size_t(i)]))
            fail(ctx, acc, "key time " + std::to_string(i) + " is not finite");
        if (i > 0 && !(times[size_t(i)] > times[size_t(i - 1)]))
            fail(ctx, acc,
                 "key times not strictly increasing (key " + std::to_string(i) +
                     " is not after key " + std::to_string(i - 1) + ")");
    }
    return times;
}

// The values: VEC3 FLOAT for translation and scale; VEC4 FLOAT or normalized (unsigned) byte or
// short for rotation (spec 3.11's table); 1 a key, 3 for CUBICSPLINE; finite; key quaternions not
// zero.
std::vector<glm::dvec4> readValues(const Context& ctx, const tinygltf::Model& model,
                                   const Json& doc, int accessor, const std::string& field,
                                   const AnimationTrack& track) {
    const std::string acc = idx("accessors", size_t(std::max(accessor, 0)));
    const bool rotation = track.property == AnimatedProperty::Rotation;
    AccessorData a = checkedAccessor(
        ctx, model, doc, accessor, field + ".output", [&](const tinygltf::Accessor& x) {
            const bool isFloat = x.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
            const bool normInt =
                x.normalized && (x.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
                                 x.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                 x.componentType == TINYGLTF_COMPONENT_TYPE_SHORT ||
                                 x.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
            if (rotation ? (x.type != TINYGLTF_TYPE_VEC4 || !(isFloat || normInt))
                         : (x.type != TINYGLTF_TYPE_VEC3 || !isFloat))
                fail(ctx, acc,
                     rotation ? "a rotation's output must be VEC4 FLOAT or normalized integers"
                              : std::string("a ") + propertyName(track.property) +
                                    "'s output must be VEC3 FLOAT");
        });
    const bool cubic = track.interpolation == AnimationInterpolation::CubicSpline;
    const uint64_t want = uint64_t(track.times.size()) * (cubic ? 3 : 1);
    if (a.count != want)
        fail(ctx, acc + ".count",
             std::to_string(a.count) + " values for " + std::to_string(track.times.size()) +
                 " keys (" + (cubic ? "CUBICSPLINE needs 3 a key: " : "needs one a key: ") +
                 std::to_string(want) + ")");
    std::vector<glm::dvec4> values(size_t(a.count), glm::dvec4(0.0));
    const int components = rotation ? 4 : 3;
    for (uint64_t i = 0; i < a.count; ++i) {
        for (int c = 0; c < components; ++c) values[size_t(i)][c] = readComponent(a, i, c);
        const glm::dvec4& v = values[size_t(i)];
        if (!(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w)))
            fail(ctx, acc, "value " + std::to_string(i) + " is not finite");
        const bool isKey = !cubic || i % 3 == 1;
        if (rotation && isKey && glm::dot(v, v) == 0.0)
            fail(ctx, acc, "value " + std::to_string(i) + " is a zero quaternion");
    }
    return values;
}

// The node's own TRS, from which an animated property departs (the loader's localTransform has
// checked or will check each array).
std::shared_ptr<AnimatedNode> nodeAtRest(const tinygltf::Node& n) {
    auto node = std::make_shared<AnimatedNode>();
    if (n.translation.size() == 3)
        node->translation = glm::dvec3(n.translation[0], n.translation[1], n.translation[2]);
    if (n.rotation.size() == 4) {
        glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
        const double len = glm::length(q);
        if (len > 0.0 && std::isfinite(len)) node->rotation = q / len;
    }
    if (n.scale.size() == 3) node->scale = glm::dvec3(n.scale[0], n.scale[1], n.scale[2]);
    return node;
}

AnimatedProperty propertyOf(const Context& ctx, const std::string& path, const std::string& field) {
    if (path == "translation") return AnimatedProperty::Translation;
    if (path == "rotation") return AnimatedProperty::Rotation;
    if (path == "scale") return AnimatedProperty::Scale;
    if (path == "weights") fail(ctx, field, "skinning and morph targets are not supported yet");
    fail(ctx, field,
         "unknown path " + quoted(printable(path, 40)) + " (valid: translation, rotation, scale)");
}

// One played channel: checked, read, and added to its node.
void addChannel(const Context& ctx, const tinygltf::Model& model, const Json& doc, size_t ai,
                size_t ci, std::vector<std::shared_ptr<AnimatedNode>>& nodes, uint64_t& keys) {
    const tinygltf::Animation& anim = model.animations[ai];
    const tinygltf::AnimationChannel& ch = anim.channels[ci];
    const std::string field = idx("animations", ai) + "." + idx("channels", ci);
    if (ch.target_node < 0 || size_t(ch.target_node) >= model.nodes.size())
        fail(ctx, field + ".target.node",
             std::to_string(ch.target_node) + " out of range (" +
                 std::to_string(model.nodes.size()) + " nodes)");
    AnimationTrack track;
    track.property = propertyOf(ctx, ch.target_path, field + ".target.path");
    const size_t ni = size_t(ch.target_node);
    const tinygltf::Node& target = model.nodes[ni];
    if (!target.matrix.empty())
        fail(ctx, field + ".target.node",
             idx("nodes", ni) + " has a matrix, which an animation may not target");
    if (ch.sampler < 0 || size_t(ch.sampler) >= anim.samplers.size())
        fail(ctx, field + ".sampler",
             std::to_string(ch.sampler) + " out of range (" + std::to_string(anim.samplers.size()) +
                 " samplers)");
    const tinygltf::AnimationSampler& s = anim.samplers[size_t(ch.sampler)];
    const std::string sField = idx("animations", ai) + "." + idx("samplers", size_t(ch.sampler));
    track.interpolation = interpolationOf(ctx, s.interpolation, sField);
    track.times = readTimes(ctx, model, doc, s.input, sField);
    keys += track.times.size();
    if (keys > ctx.limits.maxAnimationKeys)
        fail(ctx, "animations",
             "the played clips hold more than " + std::to_string(ctx.limits.maxAnimationKeys) +
                 " keys (maxAnimationKeys)");
    track.values = readValues(ctx, model, doc, s.output, sField, track);
    if (!nodes[ni]) nodes[ni] = nodeAtRest(target);
    for (const AnimationTrack& other : nodes[ni]->tracks)
        if (other.property == track.property)
            fail(ctx, field,
                 idx("nodes", ni) + "." + propertyName(track.property) +
                     " is animated twice (name one clip in the scene's sequence.animation)");
    nodes[ni]->tracks.push_back(std::move(track));
}

}  // namespace

std::vector<std::string> animationNames(const tinygltf::Model& model) {
    std::vector<std::string> names;
    for (size_t i = 0; i < model.animations.size(); ++i)
        names.push_back(model.animations[i].name.empty() ? idx("animations", i)
                                                         : printable(model.animations[i].name, 60));
    return names;
}

std::vector<std::shared_ptr<const AnimatedNode>> playedAnimations(const Context& ctx,
                                                                  const tinygltf::Model& model,
                                                                  const Json& doc,
                                                                  const std::string& clip) {
    std::vector<std::shared_ptr<AnimatedNode>> nodes(model.nodes.size());
    uint64_t keys = 0;
    for (size_t ai = 0; ai < model.animations.size(); ++ai) {
        if (!clip.empty() && model.animations[ai].name != clip) continue;
        for (size_t ci = 0; ci < model.animations[ai].channels.size(); ++ci)
            addChannel(ctx, model, doc, ai, ci, nodes, keys);
    }
    return {nodes.begin(), nodes.end()};
}

std::shared_ptr<MeshAnimation> meshAnimation(
    const Context& ctx, const tinygltf::Model& model, const std::vector<ChainLink>& links,
    const Instance& inst, const glm::dmat4& wsFromFile,
    std::vector<std::shared_ptr<const AnimatedNode>>& still) {
    if (inst.link < 0 || !links[size_t(inst.link)].moving) return nullptr;
    if (model.nodes[inst.node].skin >= 0)
        fail(ctx, idx("nodes", inst.node) + ".skin",
             "an animation moves this skinned mesh: skinning and morph targets are not supported "
             "yet");
    auto animation = std::make_shared<MeshAnimation>();
    animation->wsFromFile = wsFromFile;
    for (int64_t l = inst.link; l >= 0; l = links[size_t(l)].parent) {
        const size_t node = links[size_t(l)].node;
        if (ctx.animates(node)) {
            animation->chain.push_back(ctx.animatedNodes[node]);
            continue;
        }
        if (!still[node]) {
            auto n = std::make_shared<AnimatedNode>();
            n->restLocal = localTransform(ctx, model.nodes[node], node);
            still[node] = std::move(n);
        }
        animation->chain.push_back(still[node]);
    }
    std::reverse(animation->chain.begin(), animation->chain.end());
    return animation;
}

void readAnimations(Context& ctx, const tinygltf::Model& model, const Json& doc) {
    if (!ctx.playAnimations) return;
    GltfContent& out = *ctx.out;
    out.animationNames = animationNames(model);
    out.animationClipFound =
        ctx.animationClip.empty() ||
        std::any_of(model.animations.begin(), model.animations.end(),
                    [&](const tinygltf::Animation& a) { return a.name == ctx.animationClip; });
    ctx.animatedNodes = playedAnimations(ctx, model, doc, ctx.animationClip);
}

}  // namespace so::gltf_detail
