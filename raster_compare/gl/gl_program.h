// GLSL programs: compiled from the embedded shader files (shaders.h) with a variant's #defines
// after "#version", and the uniform setters every pass uses (values given in double, set as float).
#pragma once

#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "raster_compare/gl/gl_object.h"

namespace so {

// "#version 450 core", the defines, SO_VERTEX_SHADER or SO_FRAGMENT_SHADER defined, then each
// source in order (a frame and the technique's file).
// Compile and link errors throw std::runtime_error with the driver's log.
GlProgram buildProgram(const std::string& defines, const char* vertexSource,
                       const std::vector<const char*>& fragmentSources);

void setMat4(GLuint program, const char* name, const glm::dmat4& m);
void setVec3(GLuint program, const char* name, const glm::dvec3& v);
void setFloat(GLuint program, const char* name, double v);
void setInt(GLuint program, const char* name, int v);

// A whole texture level as floats, rows flipped to the top-first order of docs/conventions.md
// (GL's row 0 is the bottom).
std::vector<float> readTextureTopFirst(GLuint texture, GLenum format, int components, int width,
                                       int height);

}  // namespace so
