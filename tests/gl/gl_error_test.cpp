// GL errors reach the caller as GlError (issue 30): the debug callback, which runs inside the
// driver, only records them; the renderer asks the context after each technique's frame. The
// driver's warnings wait in the context for the caller to print. Label "gl".
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include "gl_test_context.h"
#include "raster_compare/gl/render/renderer.h"
#include "raster_compare/gl/technique.h"
#include "test_scenes.h"

namespace so::test {
namespace {

constexpr GLenum kNoSuchCapability = 0xDEAD;  // glEnable: GL_INVALID_ENUM

// A technique whose shadow pass makes a GL error, as a buggy one would.
class BrokenLight final : public LightTechnique {
  public:
    std::vector<std::string> passNames() const override { return {"broken"}; }
    void renderLightPasses(PassClock&) override { glEnable(kNoSuchCapability); }
    void renderVisibility(PassClock&) override {}
    RasterLightStats describe() const override { return {}; }
    uint64_t memoryBytes() const override { return 0; }
};

class Broken final : public Technique {
  public:
    Broken() : Technique(parseParams("broken", {}, {})) {}
    std::unique_ptr<LightTechnique> setUp(const LightSetup&) const override {
        return std::make_unique<BrokenLight>();
    }
};

RasterOptions quick() {
    RasterOptions o;
    o.frames = 1;
    o.warmup = 0;
    return o;
}

// The frame that made the error is named: the counted frame (docs/metrics.md, Work) comes first;
// without it, the first timed frame.
TEST(GlErrors, AnErrorInATechniqueReachesTheCallerAsGlError) {
    REQUIRE_GL();
    ASSERT_NO_THROW(gl->throwIfError()) << "no error pending from earlier tests";
    const Scene scene = makeSquareOccluderScene(32, 24).scene;
    for (bool counted : {true, false}) {
        RasterOptions options = quick();
        options.countWork = counted;
        try {
            renderRaster(scene, Broken(), options, *gl);
            FAIL() << "the GL error should have been thrown";
        } catch (const GlError& e) {
            const std::string what = e.what();
            EXPECT_EQ(what.rfind("GL error: ", 0), 0u) << what;
            // The technique is unnamed.
            EXPECT_NE(
                what.find(counted ? " [technique , counted frame]" : " [technique , frame 0]"),
                std::string::npos)
                << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
            std::printf("[ gl ] %s\n", what.c_str());
        }
        // The error was taken, and the context still renders.
        EXPECT_NO_THROW(gl->throwIfError());
    }
    EXPECT_NO_THROW(renderRaster(scene, *createTechnique("basic", {}), quick(), *gl));
}

TEST(GlErrors, ErrorsAreThrownOnceAndWarningsCollected) {
    REQUIRE_GL();
    glEnable(kNoSuchCapability);
    glEnable(kNoSuchCapability);
    try {
        gl->throwIfError();
        FAIL() << "GL_INVALID_ENUM should have been thrown";
    } catch (const GlError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("GL error: ", 0), 0u) << e.what();
    }
    EXPECT_NO_THROW(gl->throwIfError());

    gl->takeWarnings();
    glDebugMessageInsert(GL_DEBUG_SOURCE_APPLICATION, GL_DEBUG_TYPE_OTHER, 1,
                         GL_DEBUG_SEVERITY_HIGH, -1, "a warning\nover two lines");
    const std::vector<std::string> warnings = gl->takeWarnings();
    EXPECT_EQ(warnings, std::vector<std::string>{"GL: a warning\\x0aover two lines"});
    EXPECT_TRUE(gl->takeWarnings().empty());
    EXPECT_NO_THROW(gl->throwIfError()) << "a warning is no error";
}

}  // namespace
}  // namespace so::test
