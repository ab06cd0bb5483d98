// Typed parameters where a row is made (raster_compare/pipeline/row_parameters.h): a method's
// index in metrics.json gets its name from the technique's parameter table, once, so that no
// report maps an index back to a name or parses a label.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "raster_compare/pipeline/row_parameters.h"

namespace so::test {
namespace {

using K = ParamValue::Kind;

TEST(RowParameters, AMethodIsNamedByItsTechniquesTable) {
    const RowParameters p =
        typedParameters("pcf", {{"contact", 1}, {"resolution", 2048}, {"contact_steps", 8}});
    EXPECT_EQ(p.at("contact").kind, K::Name);
    EXPECT_EQ(p.at("contact").name, "on");
    EXPECT_EQ(p.at("contact").number, 1.0);
    EXPECT_EQ(p.at("resolution").kind, K::Integer);
    EXPECT_EQ(p.at("resolution").text(), "2048");
    // A swept value arrives as a double: the same name.
    EXPECT_EQ(typedParamValue("pcf", "contact", 0.0).text(), "off");
}

TEST(RowParameters, ImagesAndUnknownNamesKeepTheirJsonKinds) {
    const RowParameters p = typedParameters("external", {{"contact", "on"}, {"spp", 4.5}});
    EXPECT_EQ(p.at("contact").kind, K::Name);
    EXPECT_EQ(p.at("contact").text(), "on");
    EXPECT_EQ(p.at("spp").kind, K::Number);
    EXPECT_EQ(typedParamValue("pcf", "no_such_parameter", 1).kind, K::Integer);
    EXPECT_EQ(typedParamValue("pcf", "contact", 7).kind, K::Integer) << "no method has index 7";
    EXPECT_TRUE(typedParameters("pcf", nlohmann::json::array()).empty());
}

}  // namespace
}  // namespace so::test
