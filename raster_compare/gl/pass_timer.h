// GL time per pass with GL_TIME_ELAPSED queries, read after the frame so the GPU never stalls
// mid-frame; medians over the timed frames. (On llvmpipe the queries measure CPU work.)
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/timing.h"
#include "raster_compare/gl/gl_object.h"

namespace so {

class PassTimer {
  public:
    void begin(const std::string& pass);
    void end();
    // Reads this frame's queries, summing a pass that ran several times; kept only when `keep`
    // (warm-up frames are dropped).
    void endFrame(bool keep);
    // Median and quartiles over the kept frames (0 when the pass never ran).
    TimingStats stats(const std::string& pass) const;

  private:
    struct Query {
        std::string pass;
        GlQuery query;
    };
    std::vector<Query> frame_;
    std::map<std::string, std::vector<double>> msByPass_;
};

// What a technique times its passes with: begin("shadow_map") ... end(), one pass at a time (GL
// timer queries do not nest), recorded as "<light>.<pass>".
class PassClock {
  public:
    PassClock(PassTimer& timer, std::string light) : timer_(timer), light_(std::move(light)) {}
    void begin(const std::string& pass) { timer_.begin(light_ + "." + pass); }
    void end() { timer_.end(); }

  private:
    PassTimer& timer_;
    std::string light_;
};

}  // namespace so
