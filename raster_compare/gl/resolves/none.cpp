// resolve=none: the frame as it falls, its turning taps' noise unresolved, as three.js users see
// it (three.js has no TAA of its lit image; its TAARenderPass add-on accumulates a still camera's
// frames and is not part of its renderer).
#include "raster_compare/gl/resolves/resolve.h"

namespace so {
namespace {

class NoResolve final : public Resolve {
  public:
    static constexpr int kNumber = 0;
    static Provenance provenance() {
        return {"three.js r182 WebGLRenderer: nothing accumulates a frame's shadow over frames",
                Fidelity::Faithful};
    }
    static ParamTable params() { return {}; }
    explicit NoResolve(const ParamValues&) {}
    std::vector<std::string> passNames() const override { return {}; }
    std::unique_ptr<LightResolve> setUp(const ResolveSetup&) const override { return nullptr; }
};

}  // namespace

SO_REGISTER_RESOLVE(NoResolve, "none",
                    "the frame as it falls: the turning taps' noise unresolved (three.js)");

}  // namespace so
