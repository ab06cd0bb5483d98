// Independent random samples of an area light, for the references that judge the oracle (the
// verifier, tests/oracle/rqmc_coverage_test.cpp): SplitMix64 numbers, unrelated to the oracle's
// Sobol sequences, and points uniform by area on the rect, the disk, the polygon (a triangle of its
// fan by area, then uniform in it) or the whole sphere, in the local frame. Deliberately simple:
// correctness over speed.
#pragma once

#include <cstdint>
#include <memory>

#include <glm/vec3.hpp>

#include "core/local_frame.h"
#include "core/scene.h"

namespace so {

// SplitMix64 (Steele, Lea and Flood 2014).
struct SplitMix {
    uint64_t s;
    uint64_t next() {
        uint64_t z = (s += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double uniform() { return double(next() >> 11) * 0x1.0p-53; }  // [0, 1)
};

// One area light's independent samples: each kind makes its own (oracle/lights/, reference()).
class ReferenceSampler {
  public:
    virtual ~ReferenceSampler() = default;
    // The point for (u1, u2) in [0, 1)^2, uniform by area, and the light's outward normal there
    // (one-sided lights: the side they emit on), local frame.
    virtual void point(double u1, double u2, glm::dvec3& lsY, glm::dvec3& normal) const = 0;
};

class ReferenceLight {
  public:
    ReferenceLight(const Light& light, const LocalFrame& frame);
    void point(double u1, double u2, glm::dvec3& lsY, glm::dvec3& normal) const {
        sampler_->point(u1, u2, lsY, normal);
    }

  private:
    std::shared_ptr<const ReferenceSampler> sampler_;
};

}  // namespace so
