// The camera conventions of docs/conventions.md, which both paths rely on.
#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/trigonometric.hpp>

#include "core/camera.h"

namespace so {
namespace {

CameraDesc desc(int w, int h) {
    CameraDesc d;
    d.wsEye = {1, 2, 3};
    d.wsTarget = {1, 2, -7};  // looking down -Z
    d.wsUp = {0, 1, 0};
    d.vfovDeg = 60;
    d.width = w;
    d.height = h;
    return d;
}

TEST(Camera, CentrePixelLooksAtTargetForOddSizes) {
    Camera cam(desc(101, 51));
    Ray3d r = cam.generateRay(50, 25);
    EXPECT_NEAR(r.direction.x, 0.0, 1e-15);
    EXPECT_NEAR(r.direction.y, 0.0, 1e-15);
    EXPECT_NEAR(r.direction.z, -1.0, 1e-15);
    EXPECT_EQ(r.origin, glm::dvec3(1, 2, 3));
}

TEST(Camera, RowZeroIsTopAndColumnZeroIsLeft) {
    Camera cam(desc(64, 32));
    Ray3d topLeft = cam.generateRay(0, 0);
    EXPECT_GT(topLeft.direction.y, 0.0);  // up
    EXPECT_LT(topLeft.direction.x, 0.0);  // left, for a camera looking down -Z with +Y up
}

TEST(Camera, PixelCentresAndFullVerticalFov) {
    Camera cam(desc(64, 32));
    Ray3d a = cam.generateRay(3, 7);
    Ray3d b = cam.generateRay(3.5, 7.5);
    EXPECT_EQ(a.direction, b.direction);
    // The top edge of the image (imageY = 0) is at half the vertical fov above the axis.
    Ray3d top = cam.generateRay(32.0, 0.0);
    EXPECT_NEAR(glm::degrees(std::acos(glm::dot(top.direction, cam.wsForward()))), 30.0, 1e-12);
    // Square pixels: the left edge is at atan(aspect * tan(30 deg)).
    Ray3d left = cam.generateRay(0.0, 16.0);
    EXPECT_NEAR(std::acos(glm::dot(left.direction, cam.wsForward())),
                std::atan(2.0 * std::tan(glm::radians(30.0))), 1e-12);
}

// The raster path's matrices must put every pixel's ray through that pixel's centre.
TEST(Camera, GlMatricesAgreeWithGeneratedRays) {
    Camera cam(desc(80, 60));
    glm::dmat4 clipFromWorld = cam.clipFromView(0.1, 100.0) * cam.viewFromWorld();
    for (int y : {0, 17, 59})
        for (int x : {0, 40, 79}) {
            Ray3d r = cam.generateRay(x, y);
            glm::dvec4 clip = clipFromWorld * glm::dvec4(r.origin + 7.0 * r.direction, 1.0);
            double winX = (clip.x / clip.w * 0.5 + 0.5) * 80.0;
            double winY = (clip.y / clip.w * 0.5 + 0.5) * 60.0;  // GL: origin at the bottom
            EXPECT_NEAR(winX, x + 0.5, 1e-9);
            EXPECT_NEAR(winY, 60.0 - (y + 0.5), 1e-9);
            EXPECT_GT(clip.w, 0.0);
        }
}

TEST(Camera, DefaultFramingSeesTheWholeBounds) {
    Bounds3d b;
    b.extend({-3, 0, -1});
    b.extend({5, 2, 4});
    Camera cam(defaultFraming(b));
    glm::dmat4 clipFromWorld = cam.clipFromView(0.01, 1000.0) * cam.viewFromWorld();
    for (int k = 0; k < 8; ++k) {
        glm::dvec3 corner((k & 1) ? b.hi.x : b.lo.x, (k & 2) ? b.hi.y : b.lo.y,
                          (k & 4) ? b.hi.z : b.lo.z);
        glm::dvec4 c = clipFromWorld * glm::dvec4(corner, 1.0);
        EXPECT_LE(std::abs(c.x / c.w), 1.0);
        EXPECT_LE(std::abs(c.y / c.w), 1.0);
    }
}

}  // namespace
}  // namespace so
