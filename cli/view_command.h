// `shadow-oracle view`: the exact view another renderer must reproduce, so that its shadow images
// can be judged pixel for pixel (docs/external.md): view.json (camera and light matrices in the
// OpenGL and Vulkan conventions, lights, geometry) and gbuffer.exr (the oracle's primary hits).
#pragma once

#include <string>

#include <nlohmann/json_fwd.hpp>

#include "core/scene.h"
#include "oracle/oracle.h"

namespace so {

struct ViewCommandOptions {
    std::string scenePath;
    std::string outDir;
    OracleOptions oracle;  // width, height, threads
    bool progress = true;  // --quiet: false
};

int runViewCommand(const ViewCommandOptions& options);

// The camera's near and far planes that view.json records (docs/external.md): far just beyond the
// farthest corner of the scene's bounds, near just before the bounds (at least far / 10^5).
void viewDepthRange(const Camera& camera, const Bounds3d& wsBounds, double& near, double& far);

inline constexpr int kViewFormat = 1;

}  // namespace so
