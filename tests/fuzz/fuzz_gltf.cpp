// Fuzzes the glTF loader (core/gltf_loader.cpp). The first byte of the input picks the form:
//   bit 0 clear: the rest is a .glb file;
//   bit 0 set:   the rest, up to the first NUL byte, is a .gltf file and what follows the NUL is
//                written beside it as b.bin, the buffer file the JSON may reference;
//   bit 1 clear: loaded with loadGltf, and every file it read must lie inside the glTF's folder
//                (a canary file outside it, ../outside.bin, must never be read);
//   bit 1 set:   loaded with loadScene, as `shadow-oracle` does for a bare .gltf/.glb;
//   bit 2 set:   (with loadGltf) as a scene with a sequence loads it: its animations play, and
//                the moving meshes are posed at a few times (core/gltf_animation.h).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include <glm/mat4x4.hpp>

#include "core/gltf_animation.h"
#include "core/gltf_loader.h"
#include "core/scene.h"
#include "tests/fuzz/fuzz_common.h"

namespace {

namespace fs = std::filesystem;

const fs::path& gltfFolder() {
    static const fs::path folder = [] {
        // A valid 44-byte buffer (one triangle) outside the folder: reading it would be a finding.
        so::fuzz::writeFile(so::fuzz::scratchDir() / "outside.bin",
                            std::string_view("\0\0\0\0\0\0\0\0\0\0\0\0\0\0\x80?\0\0\0\0\0\0\0\0"
                                             "\0\0\0\0\0\0\0\0\0\0\x80\xbf\0\0\x01\0\x02\0\0\0",
                                             44));
        fs::path f = so::fuzz::scratchDir() / "gltf";
        fs::create_directories(f);
        return fs::canonical(f);
    }();
    return folder;
}

void checkFilesInside(const so::GltfContent& g) {
    for (const fs::path& read : g.filesRead) {
        std::error_code ec;
        fs::path c = fs::weakly_canonical(read, ec);
        fs::path rel = c.lexically_relative(gltfFolder());
        if (ec || rel.empty() || *rel.begin() == "..") {
            std::fprintf(stderr, "so-fuzz: FINDING: the loader read %s, outside %s\n", read.c_str(),
                         gltfFolder().c_str());
            std::abort();
        }
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    const uint8_t mode = data[0];
    std::string_view rest(reinterpret_cast<const char*>(data + 1), size - 1);
    const fs::path& folder = gltfFolder();
    fs::path path;
    std::error_code ec;
    if (mode & 1) {
        size_t nul = rest.find('\0');
        path = folder / "m.gltf";
        so::fuzz::writeFile(path, rest.substr(0, nul));
        if (nul != std::string_view::npos)
            so::fuzz::writeFile(folder / "b.bin", rest.substr(nul + 1));
        else
            fs::remove(folder / "b.bin", ec);
        fs::remove(folder / "m.glb", ec);
    } else {
        path = folder / "m.glb";
        so::fuzz::writeFile(path, rest);
        fs::remove(folder / "m.gltf", ec);
        fs::remove(folder / "b.bin", ec);
    }
    so::fuzz::expectOnlyInputErrors([&] {
        if (mode & 2) {
            so::loadScene(path, so::fuzz::fuzzLimits());
        } else {
            const so::Sequence sequence{4, 30.0, ""};
            so::GltfContent g =
                so::loadGltf(path, path.filename().string(), glm::dmat4(1.0),
                             so::fuzz::fuzzLimits(), true, (mode & 4) ? &sequence : nullptr);
            checkFilesInside(g);
            for (const so::MeshPrimitive& m : g.meshes)
                if (m.animation)
                    for (double t : {-1.0, 0.0, 0.04, 1e9}) (void)m.animation->worldAt(t);
        }
    });
    return 0;
}
