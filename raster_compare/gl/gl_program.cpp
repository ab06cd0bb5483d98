#include "raster_compare/gl/gl_program.h"

#include <algorithm>
#include <stdexcept>

#include <glm/gtc/type_ptr.hpp>

namespace so {

namespace {

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

GlProgram buildProgram(const std::string& defines, const char* vertexSource,
                       const std::vector<const char*>& fragmentSources) {
    // SO_VERTEX_SHADER or SO_FRAGMENT_SHADER tells a file that holds both stages which it is.
    const std::string header = "#version 450 core\n" + defines;
    GlShader vs = compileShader(GL_VERTEX_SHADER,
                                {header + "#define SO_VERTEX_SHADER\n#line 1\n", vertexSource});
    std::vector<std::string> fragment = {header + "#define SO_FRAGMENT_SHADER\n#line 1\n"};
    for (const char* src : fragmentSources) fragment.emplace_back(src);
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
