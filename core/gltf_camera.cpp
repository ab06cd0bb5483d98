#include "core/gltf_camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace so::gltf_detail {

void addCamera(const Context& ctx, const tinygltf::Model& model, const Instance& inst,
               std::optional<CameraDesc>& camera, bool& cameraSeen) {
    const tinygltf::Node& node = model.nodes[inst.node];
    if (node.camera < 0 || cameraSeen) return;
    cameraSeen = true;
    const tinygltf::Camera& cam = model.cameras[size_t(node.camera)];
    std::string field = idx("cameras", size_t(node.camera));
    if (cam.type != "perspective") {
        ctx.out->warnings.push_back(field + ": " + printable(cam.type) +
                                    " camera ignored (only perspective cameras are used)");
        return;
    }
    double yfov = cam.perspective.yfov * 180.0 / std::numbers::pi;
    if (!(yfov > 0.0 && yfov < 180.0))
        fail(ctx, field + ".perspective.yfov", "must be in (0, pi) radians");
    std::string nodeField = idx("nodes", inst.node);
    CameraDesc c;
    c.wsEye = glm::dvec3(inst.world * glm::dvec4(0.0, 0.0, 0.0, 1.0));
    c.wsTarget = c.wsEye + unitDirection(ctx, inst.world, {0.0, 0.0, -1.0}, nodeField);
    c.wsUp = unitDirection(ctx, inst.world, {0.0, 1.0, 0.0}, nodeField);
    c.vfovDeg = yfov;
    const double side = std::max(1, ctx.limits.maxImageSide);
    double ar = cam.perspective.aspectRatio;
    // Clamped as doubles: converting an out-of-range double to int is undefined.
    c.height = int(std::min(512.0, side));
    c.width = int(ar > 0.0 ? std::clamp(std::round(512.0 * ar), 1.0, side) : std::min(512.0, side));
    camera = c;
}

}  // namespace so::gltf_detail
