#include "core/geometry_channels.h"

#include <limits>

#include "core/channels.h"

namespace so {

GeometryChannelWriter::GeometryChannelWriter(ChannelImage& image) {
    namespace ch = channels;
    hit_ = image.addChannel(ch::kHit);
    position_[0] = image.addChannel(ch::kPX);
    position_[1] = image.addChannel(ch::kPY);
    position_[2] = image.addChannel(ch::kPZ);
    normal_[0] = image.addChannel(ch::kNX);
    normal_[1] = image.addChannel(ch::kNY);
    normal_[2] = image.addChannel(ch::kNZ);
    depth_ = image.addChannel(ch::kDepth, std::numeric_limits<float>::infinity());
    meshId_ = image.addChannel(ch::kMeshId, -1.0f);
    primId_ = image.addChannel(ch::kPrimId, -1.0f);
}

void GeometryChannelWriter::set(size_t i, const glm::dvec3& ws, const glm::vec3& n, float depth,
                                float meshId, float primId) {
    hit_[i] = 1.0f;
    for (int k = 0; k < 3; ++k) {
        position_[k][i] = float(ws[k]);
        normal_[k][i] = n[k];
    }
    depth_[i] = depth;
    meshId_[i] = meshId;
    primId_[i] = primId;
}

}  // namespace so
