// The moment blur of a cube map across its faces (shadow_map.cpp): a separable Gaussian (sigma =
// radius / 2, taps to radius) in the plane of each face, extended beyond the face, so that near a
// seam the taps come from the neighbouring face by direction instead of stopping at the edge.
// ACROSS: along the face's s axis, from the unblurred cube (its bilinear, seamless lookup), into
// a layer of RADIUS extra rows above and below the face; else along t, from that layer, into the
// face. Defines: ACROSS; SOURCE_TEXEL_BYTES and SOURCE_TAP_TEXELS, for the work counts' SO_TAP.
uniform int u_face;  // GL's order: +X, -X, +Y, -Y, +Z, -Z
uniform int u_radius;
layout(location = 0) out vec4 o_value;

float gaussian(int i) {
    float sigma = max(0.5 * float(u_radius), 0.5);
    return exp(-0.5 * float(i * i) / (sigma * sigma));
}

#ifdef ACROSS
uniform samplerCube u_source;
uniform int u_size;  // the face's side in texels

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
    float texel = 2.0 / float(u_size);
    float s = gl_FragCoord.x * texel - 1.0;
    float t = (gl_FragCoord.y - float(u_radius)) * texel - 1.0;
    vec4 sum = vec4(0.0);
    float wsum = 0.0;
    for (int i = -u_radius; i <= u_radius; ++i) {
        float w = gaussian(i);
        SO_TAP(SOURCE_TAP_TEXELS, SOURCE_TEXEL_BYTES);
        sum += w * texture(u_source, faceDirection(u_face, s + float(i) * texel, t));
        wsum += w;
    }
    o_value = sum / wsum;
}
#else
uniform sampler2DArray u_source;

void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    vec4 sum = vec4(0.0);
    float wsum = 0.0;
    for (int i = -u_radius; i <= u_radius; ++i) {
        float w = gaussian(i);
        SO_TAP(1, SOURCE_TEXEL_BYTES);
        sum += w * texelFetch(u_source, ivec3(ij.x, ij.y + u_radius + i, u_face), 0);
        wsum += w;
    }
    o_value = sum / wsum;
}
#endif
