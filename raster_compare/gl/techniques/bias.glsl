// bias (bias.cpp) and back-faces (back_faces.cpp): a constant bias of BIAS_TEXELS texels.
float techniqueVisibility(Receiver r) { return depthTest(r.p, BIAS_TEXELS * r.texel); }
