// The shadow-map family's moment frame: the map pass of moment techniques (MAP_MOMENTS). It
// writes the moments of the normalised linear light depth t in [0, 1] (distance along the map's
// view axis, so cube faces and 2D maps agree); the technique's GLSL file follows and defines
// momentsOf. Defines: MOMENTS_PASS.
in vec3 v_lsPosition;
flat in vec3 v_lsFaceNormal;
uniform mat4 u_lightViewFromLocal;
uniform float u_near;
uniform float u_far;
layout(location = 0) out vec4 o_moments;

vec4 momentsOf(float t);  // the technique's file

void main() {
    alphaTest();
    float t = clamp((-(u_lightViewFromLocal * vec4(v_lsPosition, 1.0)).z - u_near) / (u_far - u_near), 0.0, 1.0);
    o_moments = momentsOf(t);
}
