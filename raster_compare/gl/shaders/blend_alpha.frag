// Planar projected shadows: the shadow's opacity, in red and alpha. One projection blends with
// (GL_ZERO, GL_ONE_MINUS_SRC_ALPHA): V (1 - alpha); several subtract it (GL_FUNC_REVERSE_SUBTRACT,
// GL_ONE, GL_ONE): V - alpha.
uniform float u_alpha;
layout(location = 0) out vec4 o_shade;
void main() {
    alphaTest();  // the projected caster's own mask: its holes cast no shadow
    o_shade = vec4(u_alpha, 0.0, 0.0, u_alpha);
}
