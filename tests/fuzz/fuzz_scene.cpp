// Fuzzes the scene file parser (core/scene_json.cpp) through loadScene with small LoadLimits. The
// input is the scene file; its folder holds a one-triangle glTF under every name the shipped scenes
// use (meshes/floor.gltf, ...), so inputs mutated from those scenes reach the geometry code.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/scene.h"
#include "tests/fuzz/fuzz_common.h"

namespace {

// tests/data/valid/tri.gltf, on one line: a buffer in a data: URI, so no second file is needed.
constexpr std::string_view kTriangle =
    R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"scene":0,"nodes":[{"mesh":0}],)"
    R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
    R"("buffers":[{"byteLength":44,"uri":"data:application/octet-stream;base64,)"
    R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAAAAAAIC/AAABAAIAAAA="}],)"
    R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},)"
    R"({"buffer":0,"byteOffset":36,"byteLength":6}],)"
    R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",)"
    R"("min":[0,0,-1],"max":[1,0,0]},)"
    R"({"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]})";

const std::filesystem::path& sceneFolder() {
    static const std::filesystem::path folder = [] {
        std::filesystem::path f = so::fuzz::scratchDir() / "scene";
        for (const char* name : {"boulder", "cylinder", "floor", "sphere", "square", "terrain",
                                 "torus", "torus_knot", "unit_box"})
            so::fuzz::writeFile(f / "meshes" / (std::string(name) + ".gltf"), kTriangle);
        so::fuzz::writeFile(f / "tri.gltf", kTriangle);
        return f;
    }();
    return folder;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::filesystem::path path = sceneFolder() / "fuzz.scene.json";
    so::fuzz::writeFile(path, std::string_view(reinterpret_cast<const char*>(data), size));
    so::fuzz::expectOnlyInputErrors([&] { so::loadScene(path, so::fuzz::fuzzLimits()); });
    return 0;
}
