// Planar projected shadows: the shadow's opacity, which blending (GL_ZERO, GL_ONE_MINUS_SRC_ALPHA)
// multiplies V by 1 - alpha with.
uniform float u_alpha;
layout(location = 0) out vec4 o_shade;
void main() { o_shade = vec4(0.0, 0.0, 0.0, u_alpha); }
