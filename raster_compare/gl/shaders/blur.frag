// One direction of a separable Gaussian blur of a moment map (sigma = radius / 2, taps to radius).
// SOURCE_TEXEL_BYTES: a source texel's bytes (point-sampled), for the work counts.
in vec2 v_uv;
uniform sampler2D u_source;
uniform vec2 u_step;  // one texel along the blur direction
uniform int u_radius;
layout(location = 0) out vec4 o_value;
void main() {
    float sigma = max(0.5 * float(u_radius), 0.5);
    vec4 sum = vec4(0.0);
    float wsum = 0.0;
    for (int i = -u_radius; i <= u_radius; ++i) {
        float w = exp(-0.5 * float(i * i) / (sigma * sigma));
        SO_TAP(1, SOURCE_TEXEL_BYTES);
        sum += w * texture(u_source, v_uv + float(i) * u_step);
        wsum += w;
    }
    o_value = sum / wsum;
}
