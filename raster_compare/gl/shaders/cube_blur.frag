// The moment blur of a cube map across its faces (shadow_map.cpp): a separable Gaussian (sigma =
// radius / 2, taps to radius) in the plane of each face, extended `radius` texels beyond the face,
// so that near a seam the taps come from the neighbouring face by direction instead of stopping
// at the edge. Three steps, each a define:
//   PAD: a layer of the padded faces, (side + 2 radius)² texels: with INSIDE the face's own texels
//        (drawn over the middle), else what the cube holds in the direction of each texel of the
//        border (drawn over its four strips: the seamless bilinear lookup crosses into the
//        neighbouring faces);
//   ACROSS: along s, from the padded face into side x (side + 2 radius) texels;
//   DOWN: along t, from those into the face.
// SOURCE_TEXEL_BYTES and SOURCE_TAP_TEXELS: for the work counts' SO_TAP.
uniform int u_face;  // GL's order: +X, -X, +Y, -Y, +Z, -Z
uniform int u_radius;
uniform int u_size;  // the face's side in texels
layout(location = 0) out vec4 o_value;

float gaussian(int i) {
    float sigma = max(0.5 * float(u_radius), 0.5);
    return exp(-0.5 * float(i * i) / (sigma * sigma));
}

#if defined(PAD) && defined(INSIDE)
uniform sampler2DArray u_source;  // the cube's faces as layers (a view)
void main() {
    SO_TAP(1, SOURCE_TEXEL_BYTES);
    o_value = texelFetch(u_source, ivec3(ivec2(gl_FragCoord.xy) - u_radius, u_face), 0);
}
#elif defined(PAD)
uniform samplerCube u_source;

// The direction through (s, t) of a face's plane, both in [-1, 1] on the face and beyond it
// outside: GL's cube map face table (GL 4.5 core, table 8.19) inverted.
vec3 faceDirection(int face, float s, float t) {
    if (face == 0) return vec3(1.0, -t, -s);
    if (face == 1) return vec3(-1.0, -t, s);
    if (face == 2) return vec3(s, 1.0, t);
    if (face == 3) return vec3(s, -1.0, -t);
    if (face == 4) return vec3(s, -t, 1.0);
    return vec3(-s, -t, -1.0);
}

void main() {
    vec2 st = (gl_FragCoord.xy - float(u_radius)) * (2.0 / float(u_size)) - 1.0;
    SO_TAP(SOURCE_TAP_TEXELS, SOURCE_TEXEL_BYTES);
    o_value = texture(u_source, faceDirection(u_face, st.x, st.y));
}
#else
uniform sampler2DArray u_source;  // ACROSS: the padded faces; DOWN: one layer, u_face 0

void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
#ifdef ACROSS
    ivec2 step = ivec2(1, 0), origin = ivec2(ij.x + u_radius, ij.y);
#else
    ivec2 step = ivec2(0, 1), origin = ivec2(ij.x, ij.y + u_radius);
#endif
    vec4 sum = vec4(0.0);
    float wsum = 0.0;
    for (int i = -u_radius; i <= u_radius; ++i) {
        float w = gaussian(i);
        SO_TAP(1, SOURCE_TEXEL_BYTES);
        sum += w * texelFetch(u_source, ivec3(origin + i * step, u_face), 0);
        wsum += w;
    }
    o_value = sum / wsum;
}
#endif
