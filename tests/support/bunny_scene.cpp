#include "bunny_scene.h"
#include "core/lights/make_light.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "test_scenes.h"

namespace so::test {

namespace fs = std::filesystem;

namespace {

constexpr const char* kTarball = "/usr/share/doc/libcgal-dev/data.tar.gz";
constexpr const char* kMember = "data/meshes/bunny00.off";

// A minimal OFF reader: "OFF", counts, vertices, then polygons fanned into triangles.
std::optional<MeshPrimitive> readOff(const fs::path& path, std::string& whyNot) {
    std::ifstream in(path);
    std::string magic;
    size_t nv = 0, nf = 0, ne = 0;
    if (!(in >> magic >> nv >> nf >> ne) || magic != "OFF" || nv > (1u << 24) || nf > (1u << 24)) {
        whyNot = path.string() + ": not an OFF file of a sensible size";
        return std::nullopt;
    }
    MeshPrimitive m;
    m.name = "bunny00.off";
    m.wsPositions.resize(nv);
    for (glm::dvec3& p : m.wsPositions)
        if (!(in >> p.x >> p.y >> p.z)) {
            whyNot = path.string() + ": truncated vertex list";
            return std::nullopt;
        }
    for (size_t f = 0; f < nf; ++f) {
        size_t k = 0;
        if (!(in >> k) || k < 3 || k > 64) {
            whyNot = path.string() + ": bad face " + std::to_string(f);
            return std::nullopt;
        }
        std::vector<uint32_t> idx(k);
        for (uint32_t& i : idx)
            if (!(in >> i) || i >= nv) {
                whyNot = path.string() + ": bad index in face " + std::to_string(f);
                return std::nullopt;
            }
        for (size_t j = 1; j + 1 < k; ++j)
            m.indices.insert(m.indices.end(), {idx[0], idx[j], idx[j + 1]});
    }
    return m;
}

}  // namespace

std::optional<MeshPrimitive> loadCgalBunny(std::string& whyNot) {
    if (!fs::exists(kTarball)) {
        whyNot = std::string("no ") + kTarball +
                 " (Debian package libcgal-demo; scripts/test installs it)";
        return std::nullopt;
    }
    const fs::path dir = fs::temp_directory_path() / ("so-bunny-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string cmd = std::string("tar -xzf ") + kTarball + " -C '" + dir.string() + "' " +
                            kMember + " 2>/dev/null";
    std::optional<MeshPrimitive> m;
    if (std::system(cmd.c_str()) != 0)
        whyNot = std::string("could not extract ") + kMember + " from " + kTarball;
    else
        m = readOff(dir / kMember, whyNot);
    std::error_code ec;
    fs::remove_all(dir, ec);
    return m;
}

const MeshPrimitive* cgalBunny(std::string& whyNot) {
    static std::string why;
    static const std::optional<MeshPrimitive> bunny = loadCgalBunny(why);
    whyNot = why;
    return bunny ? &*bunny : nullptr;
}

void useLowRectLight(Scene& scene) {
    scene.lights = {rectLight("panel", {-9.0, 3.0, 4.0}, {0.0, 0.0, -3.0}, {0.0, 2.0, 0.0})};
    scene.effects = {"hard", "penumbra"};
    finalizeScene(scene);
}

Scene makeBunnyScene(const MeshPrimitive& bunny, int width, int height) {
    Scene scene;
    MeshPrimitive b = bunny;
    // The OFF bunny spans y in [-0.4934, 0.4938]: scaled by 10, its feet rest on y = 0.
    for (glm::dvec3& p : b.wsPositions) p = 10.0 * p + glm::dvec3(0.0, 4.93434, 0.0);
    scene.meshes.push_back(std::move(b));
    scene.meshes.push_back(makeGrid({0, 0, 0}, {24, 0, 0}, {0, 0, -24}, 4, "ground"));
    scene.camera.wsEye = {-9.0, 8.0, 15.0};
    scene.camera.wsTarget = {0.0, 3.5, 0.0};
    scene.camera.vfovDeg = 45.0;
    scene.camera.width = width;
    scene.camera.height = height;
    return scene;
}

}  // namespace so::test
