#include "raster_compare/gl/denoisers/atrous.h"

#include <utility>

#include "raster_compare/gl/context/pass_timer.h"
#include "raster_compare/gl/shaders.h"

namespace so {

AtrousFilter::AtrousFilter(RayFrame& frame, const EdgeStops& stops)
    : frame_(frame), program_(frame.program("PASS_ATROUS", "", {shaders::atrous_glsl})) {
    const GLuint ap = program_.get();
    setFloat(ap, "u_sigmaLuminance", stops.luminance);
    setFloat(ap, "u_sigmaNormal", stops.normal);
    setFloat(ap, "u_sigmaDepth", stops.depth);
}

GLuint AtrousFilter::run(PassClock& clock, int levels) {
    const ScreenTarget* in = &frame_.filterA;
    const ScreenTarget* out = &frame_.filterB;
    for (int level = 0; level < levels; ++level) {
        clock.begin("atrous");
        setInt(program_.get(), "u_step", 1 << level);
        glBindTextureUnit(0, in->texture.get());
        frame_.draw(*out, program_);
        clock.end();
        const GLuint written = out->texture.get();
        std::swap(in, out);
        if (level == 0) frame_.keepHistory(written);
    }
    return in->texture.get();
}

}  // namespace so
