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

// loadCgalBunny once per process (each call extracts the tarball again): null, with the reason,
// where it is absent.
const MeshPrimitive* cgalBunny(std::string& whyNot);

// The bunny scaled by 10 (about 10 x 10 x 8 units), standing on a 24 x 24 plane at y = 0, seen
// from the front-left. `lights` are added as given; effects as given.
Scene makeBunnyScene(const MeshPrimitive& bunny, int width, int height);

// A 3 x 2 rect light low on the bunny's left ("panel", its centre at (-9, 3, 4), facing +x) as
// the scene's only light, with the "penumbra" effect: many pixels see it near their horizon.
void useLowRectLight(Scene& scene);

}  // namespace so::test
