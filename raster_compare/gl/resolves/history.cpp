// resolve=history: each light's V through a per-light history with exact motion (history.glsl),
// what no engine keeps for a filtered shadow map (only ray-traced shadow denoisers keep a
// per-light history): the ideal upper bound of a temporal resolve, with the camera's and every
// mesh's exact motion and a same-surface test no motion vector gives. It was temporal=on's only
// resolve until issue 64.
#include "raster_compare/gl/resolves/resolve.h"
#include "raster_compare/gl/resolves/resolve_frame.h"
#include "raster_compare/gl/shaders.h"

namespace so {
namespace {

class History final : public Resolve {
  public:
    static constexpr int kNumber = 2;
    static Provenance provenance() {
        return {
            "our own: a per-light history of V with exact camera and mesh motion "
            "(time/shadow_history.h), the ideal upper bound of a temporal resolve",
            Fidelity::Own};
    }
    static ParamTable params() {
        ParamSpec history = {"history",
                             0.9,
                             0.0,
                             1.0,
                             false,
                             "the history's weight in each resolved frame (exponential blend); 0: "
                             "each frame on its own"};
        history.maxExclusive = true;
        return {history, methodParam("clamp", 1, {"off", "on"},
                                     "the history clamped to the current frame's 3x3 "
                                     "neighbourhood of V (against ghosting)")};
    }
    explicit History(const ParamValues& v)
        : weight(v.real("history")), clamp(v.integer("clamp") == 1) {}
    std::vector<std::string> passNames() const override { return {"history"}; }
    std::unique_ptr<LightResolve> setUp(const ResolveSetup& setup) const override;

    double weight;
    bool clamp;
};

std::unique_ptr<LightResolve> History::setUp(const ResolveSetup& setup) const {
    return std::make_unique<OnePassResolve>(
        setup, "history",
        glslDefine("HISTORY_WEIGHT", weight) + (clamp ? "#define HISTORY_CLAMP\n" : ""),
        std::vector<const char*>{shaders::history_glsl});
}

}  // namespace

SO_REGISTER_RESOLVE(
    History, "history",
    "a per-light history of V with exact camera and mesh motion, clamped to the "
    "3x3 neighbourhood: the ideal upper bound (no engine keeps one for shadow maps)");

}  // namespace so
