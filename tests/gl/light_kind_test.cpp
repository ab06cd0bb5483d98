// The light kinds' registries as a program linking the static libraries sees them (issue 51): every
// type has a kind in each layer, registered through the lists CMake generates from the
// SO_REGISTER_*_KIND lines (cmake/so_registry.cmake), and the layers agree on which types are
// area lights. What the raster path's shaders are told (the LIGHT_* and EMITTER_* defines) comes
// from the kinds.
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/lights/light_kind.h"
#include "core/lights/make_light.h"
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

}  // namespace
}  // namespace so
