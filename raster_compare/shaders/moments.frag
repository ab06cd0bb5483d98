// Filtered techniques' shadow pass: moments of the normalised linear light depth t in [0, 1]
// (distance along the map's view axis, so cube faces and 2D maps agree):
//   VSM: (t, t^2); ESM: exp(c t); EVSM: (exp(c+ t), exp(2 c+ t), -exp(-c- t), exp(-2 c- t)).
in vec3 v_lsPosition;
flat in vec3 v_lsFaceNormal;
uniform mat4 u_lightViewFromLocal;
uniform float u_near;
uniform float u_far;
layout(location = 0) out vec4 o_moments;
void main() {
    float t = clamp((-(u_lightViewFromLocal * vec4(v_lsPosition, 1.0)).z - u_near) / (u_far - u_near), 0.0, 1.0);
#if defined(VSM)
    o_moments = vec4(t, t * t, 0.0, 0.0);
#elif defined(ESM)
    o_moments = vec4(exp(ESM_C * t), 0.0, 0.0, 0.0);
#elif defined(EVSM)
    float p = exp(EVSM_CPOS * t), n = -exp(-EVSM_CNEG * t);
    o_moments = vec4(p, p * p, n, n * n);
#endif
}
