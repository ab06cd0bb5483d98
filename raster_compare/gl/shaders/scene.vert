// Every pass draws the scene with this vertex shader: positions in the local frame
// (core/local_frame.h), one face normal per vertex (triangles are not shared, so gl_PrimitiveID
// is the triangle's index in its mesh's index buffer), and the alpha mask's uv (alpha_test.glsl).
layout(location = 0) in vec3 a_lsPosition;
layout(location = 1) in vec3 a_lsFaceNormal;
layout(location = 2) in vec2 a_uv;  // the alpha mask's (zeros where the mesh has none)
uniform mat4 u_clipFromLocal;
out vec3 v_lsPosition;
flat out vec3 v_lsFaceNormal;
out vec2 v_uv;
// The geometry and visibility passes must produce the very same depths (depth test EQUAL).
invariant gl_Position;
void main() {
    v_lsPosition = a_lsPosition;
    v_lsFaceNormal = a_lsFaceNormal;
    v_uv = a_uv;
    gl_Position = u_clipFromLocal * vec4(a_lsPosition, 1.0);
}
