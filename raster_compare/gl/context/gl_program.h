// GLSL programs: compiled from the embedded shader files (shaders.h) with a variant's #defines
// after "#version", and the uniform setters every pass uses (values given in double, set as float).
#pragma once

#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "raster_compare/gl/context/gl_object.h"

namespace so {

// "#version 450 core", the defines, SO_VERTEX_SHADER or SO_FRAGMENT_SHADER defined, then each
// source in order (a frame and the technique's file). The fragment stage also gets
// SO_TAP(texels, texelBytes), which a shader puts before each texture lookup (a tap fetching
// `texels` texels of `texelBytes` bytes each): empty, except in a counting build.
// Compile and link errors throw std::runtime_error with the driver's log.
GlProgram buildProgram(const std::string& defines, const char* vertexSource,
                       const std::vector<const char*>& fragmentSources);

// While one lives (on this thread, where the GL context is current), buildProgram makes counting
// builds (docs/metrics.md, "Work"): SO_COUNT_WORK defined; each fragment shader invocation and
// its SO_TAPs (summed by the invocation, added at its end or before it discards) add to the work
// counters, a buffer at kWorkCounterBinding that the counted frame binds (work_counter.h); main
// and discard become macros for that; and the depth and stencil tests run before the shader
// (layout(early_fragment_tests), as a GPU's early tests), except in a program whose alpha test may
// discard (shaders/alpha_test.glsl without ALPHA_TEST_OFF), where a depth or stencil write must
// wait for the shader. Early tests change nothing else in such a program's output: the shader
// writes no depth. The counting build is a program of its own: timed frames never run it.
class CountingBuild {
  public:
    CountingBuild();
    ~CountingBuild();
    CountingBuild(const CountingBuild&) = delete;
    CountingBuild& operator=(const CountingBuild&) = delete;
};
// While one lives (on this thread), buildProgram makes ordinary programs even inside a
// CountingBuild: for set-up work that no counted frame counts and whose result the timed instance
// takes over (the lightmap's bake, SetUpShared), so that it is made by the very programs that made
// it before counting existed.
class CountingPaused {
  public:
    CountingPaused();
    ~CountingPaused();
    CountingPaused(const CountingPaused&) = delete;
    CountingPaused& operator=(const CountingPaused&) = delete;

  private:
    int paused_;  // the CountingBuilds alive when it was made
};
// Whether a CountingBuild lives on this thread: what is set up now belongs to the counted frame
// (the depth probe, a diagnostic that is no part of a technique's work, is left out of it).
bool countingBuildActive();
// The shader storage binding of the work counters in a counting build: uint[6], the fragments,
// the taps and the taps' bytes, each as two 32-bit halves (low, high).
inline constexpr GLuint kWorkCounterBinding = 7;

void setMat4(GLuint program, const char* name, const glm::dmat4& m);
void setVec3(GLuint program, const char* name, const glm::dvec3& v);
void setFloat(GLuint program, const char* name, double v);
void setInt(GLuint program, const char* name, int v);

// A whole texture level as floats, rows flipped to the top-first order of docs/conventions.md
// (GL's row 0 is the bottom).
std::vector<float> readTextureTopFirst(GLuint texture, GLenum format, int components, int width,
                                       int height);

}  // namespace so
