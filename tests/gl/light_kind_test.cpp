// The light kinds' registries as a program linking the static libraries sees them (issue 51): every
// type has a kind in each layer, registered through the lists CMake generates from the
// SO_REGISTER_*_KIND lines (cmake/so_registry.cmake), and the layers agree on which types are
// area lights. What the raster path's shaders are told (the LIGHT_* and EMITTER_* defines) comes
// from the kinds.
#include <cmath>
#include <map>
#include <set>
#include <string>

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/lights/light_kind.h"
#include "core/lights/make_light.h"
#include "core/sobol.h"
#include "oracle/lights/area_light_kind.h"
#include "raster_compare/gl/lights/raster_light_kind.h"
#include "raster_compare/gl/shadow_maps/light_camera.h"

namespace so {
namespace {

TEST(LightKinds, EveryTypeHasAKindInEveryLayer) {
    const std::vector<const LightKind*>& kinds = allLightKinds();
    EXPECT_EQ(kinds.size(), kBuiltInLightKindCount);
    EXPECT_EQ(kBuiltInRasterLightKindCount, kBuiltInLightKindCount)
        << "a raster_compare/gl/lights/*.cpp registration missing or extra";
    std::set<std::string> names;
    size_t areas = 0;
    for (size_t i = 0; i < kinds.size(); ++i) {
        const LightKind& k = *kinds[i];
        const std::string name = k.name();
        EXPECT_EQ(size_t(k.type()), i) << name;
        EXPECT_TRUE(names.insert(name).second) << name;
        EXPECT_EQ(findLightKind(name), &k) << name;
        const RasterLightKind& raster = rasterLightKind(k.type());
        EXPECT_EQ(raster.type(), k.type()) << name;
        EXPECT_EQ(raster.area() != nullptr, k.isArea()) << name;
        if (k.isArea()) {
            ++areas;
            EXPECT_EQ(areaLightKind(k.type()).type(), k.type()) << name;
            EXPECT_FALSE(k.isDirectional() || k.hasCone()) << name;
        } else {
            EXPECT_THROW(areaLightKind(k.type()), InternalError) << name;
        }
    }
    EXPECT_EQ(kBuiltInAreaLightKindCount, areas)
        << "an oracle/lights/*.cpp registration missing or extra";
    EXPECT_TRUE(names.count("point") && names.count("rect") && names.count("polygon"));
}

TEST(LightKinds, ConstructorsMakeTheTypeTheyName) {
    const glm::dvec3 p{1, 2, 3}, down{0, -1, 0};
    const std::pair<Light, const char*> made[] = {
        {pointLight("a", p), "point"},
        {directionalLight("b", down), "directional"},
        {spotLight("c", p, down, 30.0, 10.0), "spot"},
        {rectLight("d", p, {1, 0, 0}, {0, 0, 1}), "rect"},
        {diskLight("e", p, down, 0.5), "disk"},
        {sphereLight("f", p, 0.5), "sphere"},
        {pointLightAt(rectLight("g", p, {1, 0, 0}, {0, 0, 1}), {4, 5, 6}), "point"}};
    for (const auto& [light, name] : made) EXPECT_STREQ(lightTypeName(light.type), name);
    EXPECT_TRUE(isDirectional(made[1].first));
    EXPECT_TRUE(hasCone(made[2].first));
    EXPECT_EQ(made[2].first.outerConeDeg, 30.0);
    EXPECT_TRUE(isOneSided(made[3].first) && isOneSided(made[4].first));
    EXPECT_FALSE(isOneSided(made[5].first));
    EXPECT_EQ(made[6].first.wsPosition, glm::dvec3(4, 5, 6));
    EXPECT_EQ(made[6].first.name, "g");
}

// The shaders' defines, as the raster files built them by hand before the kinds gave them.
TEST(LightKinds, ShaderDefinesComeFromTheKind) {
    const glm::dvec3 p{1, 2, 3}, down{0, -1, 0};
    EXPECT_EQ(lightCameraDefines(directionalLight("d", down)), "#define LIGHT_ORTHO\n");
    EXPECT_EQ(lightCameraDefines(spotLight("s", p, down, 30.0)), "#define LIGHT_SPOT\n");
    EXPECT_EQ(lightCameraDefines(pointLight("p", p)), "#define LIGHT_CUBE\n");
    EXPECT_EQ(lightCameraDefines(sphereLight("b", p, 1.0)), "#define LIGHT_CUBE\n");
    const auto emitter = [](const Light& l) {
        return std::string(rasterLightKind(l.type).emitterDefine());
    };
    EXPECT_EQ(emitter(pointLight("p", p)), "#define EMITTER_POINT\n");
    EXPECT_EQ(emitter(directionalLight("d", down)), "#define EMITTER_POINT\n");
    EXPECT_EQ(emitter(rectLight("r", p, {1, 0, 0}, {0, 0, 1})), "#define EMITTER_ONE_SIDED\n");
    EXPECT_EQ(emitter(diskLight("k", p, down, 1.0)), "#define EMITTER_ONE_SIDED\n");
    EXPECT_EQ(emitter(sphereLight("b", p, 1.0)), "#define EMITTER_SPHERE\n");
}

// A light whose every field is set, as no scene file makes one: each kind must answer from the
// fields its own type reads. The guess this replaces (smrt.cpp before issue 62: edges set, a
// rect; a radius and a normal, a disk) took every such light for a rect.
Light lightWithEveryField(const LightKind& kind) {
    Light l = rectLight("all", {1, 2, 3}, {2, 0, 0}, {0, 0, 1});
    l.type = kind.type();
    l.wsDirection = {0, -1, 0};
    l.wsNormal = {0, -1, 0};
    l.radius = 0.5;
    l.wsVertices = {{0.5, 2, 2.5}, {1.5, 2, 2.5}, {1.5, 2, 3.5}, {0.5, 2, 3.5}};
    return l;
}

TEST(LightKinds, EachRasterKindAnswersItsOwnShape) {
    using Shape = RasterLightShape::Kind;
    // By the scene format's name: a registered type missing here fails below, so a new light
    // type says which shape it is before smrt or the shadow rays can take it.
    const std::map<std::string, Shape> expected = {
        {"point", Shape::Point},    {"directional", Shape::Direction},
        {"spot", Shape::Point},     {"rect", Shape::Rect},
        {"disk", Shape::Disk},      {"sphere", Shape::Sphere},
        {"polygon", Shape::Polygon}};
    std::set<Shape> answered;
    for (const LightKind* k : allLightKinds()) {
        const auto want = expected.find(k->name());
        ASSERT_NE(want, expected.end()) << k->name() << ": no expected shape in this test";
        const Light l = lightWithEveryField(*k);
        const RasterLightShape shape = rasterLightKind(k->type()).shape(l);
        EXPECT_EQ(int(shape.kind), int(want->second)) << k->name();
        EXPECT_EQ(shape.wsCentre, l.wsPosition) << k->name();
        answered.insert(shape.kind);
    }
    EXPECT_EQ(answered.size(), 6u) << "a shape no registered kind answers";
    // What the soft techniques render each sample point with (pointLightAt): a point light that
    // keeps the rect's edges is a point.
    const Light sample = pointLightAt(rectLight("r", {1, 2, 3}, {2, 0, 0}, {0, 0, 1}), {1, 2, 3});
    EXPECT_EQ(int(rasterLightKind(sample.type).shape(sample).kind), int(Shape::Point));
}

TEST(LightKinds, ShapesGiveTheLightsGeometry) {
    const Light rect = rectLight("r", {1, 2, 3}, {2, 0, 0}, {0, 0, 1});
    const RasterLightShape r = rasterLightKind(rect.type).shape(rect);
    EXPECT_EQ(r.wsU, rect.wsU);
    EXPECT_EQ(r.wsV, rect.wsV);
    // The disk: two perpendicular semi-axes of its radius in its plane, spanning its samples.
    const Light disk = diskLight("d", {1, 2, 3}, {0, -1, 0}, 0.5);
    const RasterLightShape d = rasterLightKind(disk.type).shape(disk);
    EXPECT_NEAR(glm::length(d.wsU), 0.5, 1e-15);
    EXPECT_NEAR(glm::length(d.wsV), 0.5, 1e-15);
    EXPECT_NEAR(glm::dot(d.wsU, d.wsV), 0.0, 1e-15);
    EXPECT_NEAR(glm::dot(d.wsU, disk.wsNormal), 0.0, 1e-15);
    EXPECT_NEAR(glm::dot(d.wsV, disk.wsNormal), 0.0, 1e-15);
    const RasterAreaLightKind& area = *rasterAreaLightKind(disk.type);
    for (uint32_t i = 0; i < 64; ++i) {
        float u = 0.0f, v = 0.0f;
        sobol2D(i, 0x5eedu, u, v);
        const glm::dvec3 q = area.samplePoint(disk, u, v) - d.wsCentre;
        const double x = glm::dot(q, d.wsU) / 0.25, y = glm::dot(q, d.wsV) / 0.25;
        EXPECT_LE(x * x + y * y, 1.0 + 1e-12) << i;
        EXPECT_NEAR(glm::length(q - x * d.wsU - y * d.wsV), 0.0, 1e-12) << i;
    }
    const Light sphere = sphereLight("s", {1, 2, 3}, 0.5);
    EXPECT_EQ(rasterLightKind(sphere.type).shape(sphere).radius, 0.5);
}

// Points as a receiver sees the light: a one-sided light's samples with its emitting normal; a
// sphere's on the cap the receiver sees (cos from the axis towards it at least r / D), with the
// outward normal; inside the sphere the whole sphere's; a punctual light its one point.
TEST(LightKinds, PointsSeenFromAReceiver) {
    const glm::dvec3 c{1, 2, 3}, from{1, 0, 3};
    const Light disk = diskLight("d", c, {0, -1, 0}, 0.5);
    const Light sphere = sphereLight("s", c, 0.5);
    const RasterAreaLightKind& diskKind = *rasterAreaLightKind(disk.type);
    const RasterLightKind& sphereKind = rasterLightKind(sphere.type);
    const double cosCap = 0.5 / glm::length(from - c);
    for (uint32_t i = 0; i < 256; ++i) {
        float u = 0.0f, v = 0.0f;
        sobol2D(i, 7u, u, v);
        const LightPoint dp = diskKind.pointSeenFrom(disk, from, u, v);
        EXPECT_EQ(dp.wsPoint, diskKind.samplePoint(disk, u, v));
        EXPECT_EQ(dp.wsNormal, disk.wsEmitNormal());
        const LightPoint sp = sphereKind.pointSeenFrom(sphere, from, u, v);
        const glm::dvec3 radial = (sp.wsPoint - c) / 0.5;
        EXPECT_NEAR(glm::length(radial), 1.0, 1e-12) << i;
        EXPECT_GE(glm::dot(radial, glm::normalize(from - c)), cosCap - 1e-12) << i;
        EXPECT_NEAR(glm::length(sp.wsNormal - radial), 0.0, 1e-12) << i;
        const LightPoint inside = sphereKind.pointSeenFrom(sphere, c + glm::dvec3(0.1, 0, 0), u, v);
        EXPECT_EQ(inside.wsPoint, rasterAreaLightKind(sphere.type)->samplePoint(sphere, u, v));
    }
    const Light point = pointLight("p", c);
    const LightPoint pp = rasterLightKind(point.type).pointSeenFrom(point, from, 0.3, 0.7);
    EXPECT_EQ(pp.wsPoint, c);
    EXPECT_EQ(pp.wsNormal, glm::dvec3(0.0));
}

}  // namespace
}  // namespace so
