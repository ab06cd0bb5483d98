// The technique registry survives static linking (issue 30): this program links the static
// so_raster and names no technique, yet every techniques/*.cpp file is registered, because the
// registry calls the list CMake generates from the registration lines (technique.h).
#include <set>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "raster_compare/gl/technique.h"

namespace so {
namespace {

TEST(TechniqueRegistry, EveryTechniqueFileIsRegistered) {
    // SO_TECHNIQUE_FILE_COUNT: the techniques/*.cpp files CMake saw (tests/CMakeLists.txt). One
    // technique per file, each with its SO_REGISTER_TECHNIQUE line (CONTRIBUTING.md).
    EXPECT_EQ(kBuiltInTechniqueCount, size_t(SO_TECHNIQUE_FILE_COUNT))
        << "a techniques/*.cpp file without exactly one SO_REGISTER_TECHNIQUE line at the start "
           "of a line";
    const std::vector<const TechniqueInfo*> all = allTechniques();
    EXPECT_EQ(all.size(), kBuiltInTechniqueCount);
    std::set<std::string> names;
    for (const TechniqueInfo* t : all) {
        EXPECT_TRUE(names.insert(t->name).second) << t->name;
        EXPECT_FALSE(t->family.empty()) << t->name;
        EXPECT_NO_THROW(createTechnique(t->name, {})) << t->name;
    }
    EXPECT_TRUE(names.count("pcf") && names.count("volume-zfail") && names.count("planar"));
}

TEST(TechniqueRegistry, DuplicateNameIsDetected) {
    TechniqueRegistry registry;
    registerBuiltInTechniques(registry);
    EXPECT_EQ(registry.byName().size(), kBuiltInTechniqueCount);
    // The same list again: the first name already there throws.
    EXPECT_THROW(registerBuiltInTechniques(registry), std::invalid_argument);
    TechniqueInfo copy = registry.byName().at("pcf");
    EXPECT_THROW(registry.add(copy), std::invalid_argument);
}

TEST(TechniqueRegistry, UnknownNamesAreInputErrorsOrInvalidArguments) {
    EXPECT_THROW(findTechnique("no-such-technique"), InputError);
    const std::unique_ptr<Technique> pcf = createTechnique("pcf", {});
    EXPECT_THROW(pcf->values().real("no_such_parameter"), std::invalid_argument);
    EXPECT_THROW(methodParam("m", 0, {"only"}, "one name is no choice"), std::invalid_argument);
}

}  // namespace
}  // namespace so
