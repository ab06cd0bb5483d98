#include "raster_compare/gl/context/gl_program.h"

#include <algorithm>
#include <stdexcept>

#include <glm/gtc/type_ptr.hpp>

#include "raster_compare/gl/shaders.h"

namespace so {

namespace {

thread_local int countingBuilds = 0;  // CountingBuild objects alive on this thread

// The fragment stage's prelude (after the defines) and, in a counting build, its last source.
// Every fragment shader's main becomes soMain, called by a main that counts the invocation and
// then adds the taps it made: an invocation sums its own taps and adds them once, as contended
// atomics per tap made a blurred moment map's counted frame several times as slow. A discard ends
// the invocation before that: `discard` adds them first. The counters add with a carry into the
// high half, so that no count wraps at 2^32.
constexpr const char* kTapPrelude = "#define SO_TAP(texels, texelBytes)\n";
constexpr const char* kCountingPrelude = R"glsl(#define SO_COUNT_WORK
layout(std430, binding = 7) buffer SoWorkCounters { uint so_work[6]; };
uint so_taps = 0u, so_tapBytes = 0u;
void soAdd(int i, uint v) {
    if (v == 0u) return;
    uint before = atomicAdd(so_work[i], v);
    if (before > 0xffffffffu - v) atomicAdd(so_work[i + 1], 1u);
}
void soAddTaps() {
    soAdd(2, so_taps);
    soAdd(4, so_tapBytes);
}
void soTap(uint texels, uint texelBytes) {
    so_taps += 1u;
    so_tapBytes += texels * texelBytes;
}
#define SO_TAP(texels, texelBytes) soTap(uint(texels), uint(texelBytes))
#define discard { soAddTaps(); discard; }
#define main soMain
)glsl";
static_assert(kWorkCounterBinding == 7, "kCountingPrelude's binding");
constexpr const char* kCountingEpilogue = R"glsl(
#undef main
void main() {
    soAdd(0, 1u);
    soMain();
    soAddTaps();
}
)glsl";

// A program whose alpha test may discard keeps its depth and stencil tests after the shader.
bool mayDiscard(const std::string& defines, const std::vector<const char*>& fragmentSources) {
    return std::find(fragmentSources.begin(), fragmentSources.end(), shaders::alpha_test_glsl) !=
               fragmentSources.end() &&
           defines.find("#define ALPHA_TEST_OFF") == std::string::npos;
}

GlShader compileShader(GLenum stage, const std::vector<std::string>& sources) {
    GlShader s(glCreateShader(stage));
    std::vector<const char*> texts;
    for (const std::string& src : sources) texts.push_back(src.c_str());
    glShaderSource(s.get(), GLsizei(texts.size()), texts.data(), nullptr);
    glCompileShader(s.get());
    GLint ok = 0;
    glGetShaderiv(s.get(), GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096];
        glGetShaderInfoLog(s.get(), sizeof log, nullptr, log);
        throw std::runtime_error(std::string("shader compile failed: ") + log);
    }
    return s;
}

}  // namespace

CountingBuild::CountingBuild() {
    ++countingBuilds;
}
CountingBuild::~CountingBuild() {
    --countingBuilds;
}
bool countingBuildActive() {
    return countingBuilds > 0;
}

CountingPaused::CountingPaused() : paused_(countingBuilds) {
    countingBuilds = 0;
}
CountingPaused::~CountingPaused() {
    countingBuilds = paused_;
}

GlProgram buildProgram(const std::string& defines, const char* vertexSource,
                       const std::vector<const char*>& fragmentSources) {
    // SO_VERTEX_SHADER or SO_FRAGMENT_SHADER tells a file that holds both stages which it is.
    const std::string header = "#version 450 core\n" + defines;
    GlShader vs = compileShader(GL_VERTEX_SHADER,
                                {header + "#define SO_VERTEX_SHADER\n#line 1\n", vertexSource});
    const bool counting = countingBuilds > 0;
    std::string prelude = header + "#define SO_FRAGMENT_SHADER\n";
    if (counting && !mayDiscard(defines, fragmentSources))
        prelude += "layout(early_fragment_tests) in;\n";
    prelude += counting ? kCountingPrelude : kTapPrelude;
    std::vector<std::string> fragment = {prelude + "#line 1\n"};
    for (const char* src : fragmentSources) fragment.emplace_back(src);
    if (counting) fragment.emplace_back(kCountingEpilogue);
    GlShader fs = compileShader(GL_FRAGMENT_SHADER, fragment);
    GlProgram p(glCreateProgram());
    glAttachShader(p.get(), vs.get());
    glAttachShader(p.get(), fs.get());
    glLinkProgram(p.get());
    GLint ok = 0;
    glGetProgramiv(p.get(), GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[4096];
        glGetProgramInfoLog(p.get(), sizeof log, nullptr, log);
        throw std::runtime_error(std::string("program link failed: ") + log);
    }
    return p;
}

void setMat4(GLuint prog, const char* name, const glm::dmat4& m) {
    const glm::mat4 f(m);
    glProgramUniformMatrix4fv(prog, glGetUniformLocation(prog, name), 1, GL_FALSE,
                              glm::value_ptr(f));
}
void setVec3(GLuint prog, const char* name, const glm::dvec3& v) {
    glProgramUniform3f(prog, glGetUniformLocation(prog, name), float(v.x), float(v.y), float(v.z));
}
void setFloat(GLuint prog, const char* name, double v) {
    glProgramUniform1f(prog, glGetUniformLocation(prog, name), float(v));
}
void setInt(GLuint prog, const char* name, int v) {
    glProgramUniform1i(prog, glGetUniformLocation(prog, name), v);
}

std::vector<float> readTextureTopFirst(GLuint texture, GLenum format, int components, int width,
                                       int height) {
    const size_t row = size_t(width) * size_t(components);
    std::vector<float> gl(row * size_t(height)), top(gl.size());
    glGetTextureImage(texture, 0, format, GL_FLOAT, GLsizei(gl.size() * sizeof(float)), gl.data());
    for (int y = 0; y < height; ++y)
        std::copy_n(gl.begin() + long(size_t(height - 1 - y) * row), row,
                    top.begin() + long(size_t(y) * row));
    return top;
}

}  // namespace so
