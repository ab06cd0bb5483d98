// normal-offset (normal_offset.cpp): the lookup point moved along the normal, then a constant bias.
float techniqueVisibility(Receiver r) {
    vec3 q = r.p + r.n * (NORMAL_OFFSET_TEXELS * r.texel * (1.0 - r.ndotl));
    return depthTest(q, BIAS_TEXELS * r.texel);
}
