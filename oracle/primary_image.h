// The oracle's primary hits as an image: gbuffer.exr of `shadow-oracle view` (docs/external.md).
// Its geometry channels are oracle.exr's, bit for bit, and bary.u, bary.v let `trace --points`
// replay each hit exactly.
#pragma once

#include "core/image.h"
#include "core/scene.h"
#include "oracle/oracle.h"

namespace so {

class Accel;
struct SurfaceBuffer;

// A, P.*, N.*, Z, id.mesh, id.prim (core/geometry_channels.h) of the buffer's hits; the one
// writer of these channels for oracle.exr and gbuffer.exr.
void fillGeometryChannels(const SurfaceBuffer& sb, const Accel& accel, ChannelImage& image);

struct PrimaryImage {
    // The geometry channels and bary.u, bary.v (0 where the primary ray missed).
    ChannelImage image;
    // The hit points' bounds in the local frame both paths share (LocalFrame::fit of the scene's
    // bounds): the receivers the camera sees, as the raster path fits a directional light's map
    // to them.
    Bounds3d lsReceivers;
};

// The primary pass of runOracle alone, over the whole image of effectiveCamera(scene, options).
PrimaryImage tracePrimaryImage(const Scene& scene, const OracleOptions& options);

}  // namespace so
