// bias=receiver-plane: receiver plane depth bias (Isidoro, "Shadow Mapping: GPU-based Tips and
// Techniques", GDC 2006). The receiver's depth gradient in the map, per texel, from its
// screen-space derivatives (where the pixels to its right and above fall in the map, and how deep
// they lie: the chain rule through the map's projection), and the depth compared at the centre of
// the texel each tap reads, where the map sampled what it holds: there a receiver that is its own
// occluder has exactly the depth the map stored, so no slope factor is tuned. What is left is the
// depth buffer's rounding (`epsilon`, DepthPrecision). The derivatives see neighbouring pixels: at
// a triangle's edge or a silhouette they span two surfaces (adaptive takes the plane from the
// geometric normal instead).
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/depth_bias.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"

namespace so {
namespace {

class ReceiverPlaneDepthBias final : public DepthBias {
  public:
    static constexpr int kNumber = 6;  // bias=6 means it, fixed once given
    static ParamTable params() { return DepthPrecision::params(); }
    explicit ReceiverPlaneDepthBias(const ParamValues& v) : precision_(v) {}
    const char* glsl() const override { return shaders::receiver_plane_bias_glsl; }
    std::string defines(int depthBits) const override {
        return precision_.defines(depthBits) + "#define SCREEN_DERIVATIVES\n";
    }

  private:
    DepthPrecision precision_;
};

}  // namespace

SO_REGISTER_BIAS(ReceiverPlaneDepthBias, "receiver-plane",
                 "receiver plane depth bias (Isidoro 2006): the depth gradient from screen-space "
                 "derivatives, compared at each tap's texel centre");

}  // namespace so
