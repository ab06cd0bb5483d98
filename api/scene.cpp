// The API's scenes: a file, or meshes and a description in memory.
#include <chrono>

#include "api/api_internal.h"
#include "core/scene_pose.h"

namespace shadow_oracle {

Scene Scene::load(const std::string& path) {
    return detail::translated([&] {
        const auto t0 = std::chrono::steady_clock::now();
        so::Scene scene = so::loadScene(path);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        return Scene(std::make_shared<const Data>(Data{std::move(scene), seconds, std::nullopt}));
    });
}

Scene Scene::fromMeshes(const std::vector<Mesh>& meshes, const std::string& description) {
    return detail::translated([&] {
        std::vector<so::MeshPrimitive> prims;
        for (size_t m = 0; m < meshes.size(); ++m) {
            const Mesh& in = meshes[m];
            if (in.positions.size() % 3 != 0)
                so::throwInputError("(scene in memory)",
                                    "meshes[" + std::to_string(m) + "].vertices",
                                    "the coordinate count is not a multiple of 3");
            so::MeshPrimitive p;
            p.name = in.name.empty() ? "meshes[" + std::to_string(m) + "]" : in.name;
            p.wsPositions.reserve(in.positions.size() / 3);
            for (size_t i = 0; i + 2 < in.positions.size(); i += 3)
                p.wsPositions.emplace_back(in.positions[i], in.positions[i + 1],
                                           in.positions[i + 2]);
            p.indices = in.triangles;
            prims.push_back(std::move(p));
        }
        return Scene(std::make_shared<const Data>(
            Data{so::sceneFromMemory(description, std::move(prims)), 0.0, std::nullopt}));
    });
}

std::string Scene::path() const {
    return data_->scene.path.string();
}

std::string Scene::hash() const {
    return data_->scene.contentHash;
}

std::vector<LightInfo> Scene::lights() const {
    std::vector<LightInfo> out;
    for (const so::Light& l : data_->scene.lights)
        out.push_back({l.name, so::lightTypeName(l.type), so::isAreaLight(l.type)});
    return out;
}

std::vector<std::string> Scene::effects() const {
    return data_->scene.effects;
}

std::pair<int, int> Scene::cameraSize() const {
    return {data_->scene.camera.width, data_->scene.camera.height};
}

uint64_t Scene::triangles() const {
    return data_->scene.stats.triangles;
}

std::vector<std::string> Scene::warnings() const {
    return data_->scene.stats.warnings;
}

int Scene::frames() const {
    return data_->scene.sequence ? data_->scene.sequence->frames : 0;
}

double Scene::fps() const {
    return data_->scene.sequence ? data_->scene.sequence->fps : 0.0;
}

Scene Scene::atFrame(int k) const {
    return detail::translated([&] {
        const so::Scene& scene = data_->scene;
        const std::string file = scene.path.empty() ? "(scene in memory)" : scene.path.string();
        if (!scene.sequence)
            so::throwInputError(file, "frame",
                                "the scene has no sequence (scene_format 5, docs/scene-format.md)");
        if (k < 0 || k >= scene.sequence->frames)
            so::throwInputError(file, "frame",
                                "frame " + std::to_string(k) + " is outside the sequence's " +
                                    std::to_string(scene.sequence->frames) + " frames (0 to " +
                                    std::to_string(scene.sequence->frames - 1) + ")");
        const double t = so::sequenceTime(*scene.sequence, k);
        return Scene(std::make_shared<const Data>(
            Data{so::sceneAtTime(scene, t), data_->loadSeconds, so::SequenceFrame{k, t}}));
    });
}

}  // namespace shadow_oracle
