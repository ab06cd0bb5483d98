// The Stanford bunny from Debian's libcgal-demo (bunny00.off in its data.tar.gz: 37,706 vertices,
// 75,408 triangles), on a plane, for the tests that hold the oracle against an independent exact
// re-trace on a real scanned mesh (issue 9: closed forms on simple geometry missed a leak that
// this mesh showed).
#pragma once

#include <optional>
#include <string>

#include "core/scene.h"

namespace so::test {

// The bunny's triangles, read from the package's tarball (extracted with tar into a temporary
// folder). nullopt with the reason where the package or tar is absent: the tests then skip.
std::optional<MeshPrimitive> loadCgalBunny(std::string& whyNot);

// The bunny scaled by 10 (about 10 x 10 x 8 units), standing on a 24 x 24 plane at y = 0, seen
// from the front-left. `lights` are added as given; effects as given.
Scene makeBunnyScene(const MeshPrimitive& bunny, int width, int height);

}  // namespace so::test
