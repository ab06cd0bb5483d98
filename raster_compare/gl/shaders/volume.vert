// Shadow-volume faces: local-frame positions with w (0 at infinity, extruded from the light).
layout(location = 0) in vec4 a_lsPosition;
uniform mat4 u_clipFromLocal;
void main() { gl_Position = u_clipFromLocal * a_lsPosition; }
