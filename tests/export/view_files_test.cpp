// The export library (raster_compare/export/, so_export) called directly, not through the command:
// view.json's depth range and light cameras from a loaded scene, and a file that cannot be written
// named in one line. Label "export".
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "core/camera.h"
#include "core/error.h"
#include "core/scene.h"
#include "raster_compare/export/view_files.h"

namespace so {
namespace {

namespace fs = std::filesystem;

TEST(ViewFiles, DepthRangeHoldsTheBoundsFromJustBeforeToJustBeyond) {
    CameraDesc d;
    d.wsEye = {0.0, 0.0, 10.0};
    d.wsTarget = {0.0, 0.0, 0.0};
    const Camera camera(d);
    Bounds3d b;
    b.extend(glm::dvec3(-1.0, -1.0, -1.0));
    b.extend(glm::dvec3(1.0, 1.0, 1.0));
    double near = 0.0, far = 0.0;
    viewDepthRange(camera, b, near, far);
    // The nearest point of the box is 9 away, its farthest corner sqrt(1 + 1 + 121).
    EXPECT_LT(near, 9.0);
    EXPECT_GT(near, 0.9 * 9.0);
    EXPECT_GT(far, std::sqrt(123.0));
    EXPECT_LT(far, 1.1 * std::sqrt(123.0));
    // The eye inside the bounds: near is not 0 but far / 10^5.
    d.wsEye = {0.0, 0.0, 0.5};
    viewDepthRange(Camera(d), b, near, far);
    EXPECT_GT(near, 0.0);
    EXPECT_NEAR(near, far * 1e-5, far * 1e-12);
}

TEST(ViewFiles, ViewJsonOfALoadedSceneHasACameraAndEveryLight) {
    const fs::path out =
        fs::temp_directory_path() / ("so_view_files_test_" + std::to_string(::getpid()));
    fs::remove_all(out);
    fs::create_directories(out);
    const Scene scene = loadScene(SO_SCENES_DIR "/contact_box.scene.json");
    OracleOptions o;
    o.width = 32;
    o.height = 24;
    o.threads = 1;
    const ViewFiles files = writeViewFiles(scene, "contact_box.scene.json", o, out);
    EXPECT_TRUE(fs::exists(files.gbufferExr));
    std::ifstream in(files.viewJson);
    const nlohmann::json view = nlohmann::json::parse(in);
    EXPECT_EQ(view.at("view_format"), kViewFormat);
    const nlohmann::json& camera = view.at("camera");
    EXPECT_EQ(camera.at("width"), 32);
    EXPECT_EQ(camera.at("height"), 24);
    EXPECT_LT(camera.at("near").get<double>(), camera.at("far").get<double>());
    ASSERT_EQ(view.at("lights").size(), scene.lights.size());
    ASSERT_FALSE(scene.lights.empty());
    for (size_t i = 0; i < scene.lights.size(); ++i)
        EXPECT_EQ(view.at("lights")[i].at("name"), scene.lights[i].name);
    fs::remove_all(out);
}

TEST(ViewFiles, AFileThatCannotBeWrittenIsNamed) {
    const fs::path path = fs::temp_directory_path() / "so_view_files_no_folder" / "view.json";
    fs::remove_all(path.parent_path());
    try {
        writeFileBytes(path, "{}");
        FAIL() << "wrote into a folder that does not exist";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(path.string()), std::string::npos) << what;
        EXPECT_NE(what.find("cannot be written"), std::string::npos) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << "one line";
    }
}

}  // namespace
}  // namespace so
