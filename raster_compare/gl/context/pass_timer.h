// What a frame's passes are recorded with: GL time per pass in the timed frames (PassTimer, with
// GL_TIME_ELAPSED queries read after the frame, so the GPU never stalls mid-frame; medians over
// the timed frames; on llvmpipe the queries measure CPU work), their work in the counted frame
// (WorkCounter, work_counter.h). A technique sees neither: it names its passes to a PassClock.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/timing.h"
#include "raster_compare/gl/context/gl_object.h"

namespace so {

// One pass at a time: begin(pass) ... end().
class PassRecorder {
  public:
    virtual ~PassRecorder() = default;
    virtual void begin(const std::string& pass) = 0;
    virtual void end() = 0;
    // Shadow rays the current pass traced on the CPU (the raytraced family): counted work.
    virtual void addRays(uint64_t /*rays*/) {}
};

class PassTimer final : public PassRecorder {
  public:
    void begin(const std::string& pass) override;
    void end() override;
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

// What a technique names its passes with: begin("shadow_map") ... end(), one pass at a time (GL
// timer queries do not nest), recorded as "<light>.<pass>": timed, or counted (work_counter.h).
class PassClock {
  public:
    PassClock(PassRecorder& recorder, std::string light)
        : recorder_(recorder), light_(std::move(light)) {}
    void begin(const std::string& pass) { recorder_.begin(light_ + "." + pass); }
    void end() { recorder_.end(); }
    // Inside begin() ... end(): the pass traced `rays` shadow rays (work counts' rays_traced).
    void addRays(uint64_t rays) { recorder_.addRays(rays); }

  private:
    PassRecorder& recorder_;
    std::string light_;
};

}  // namespace so
