// basic (basic.cpp): the plain depth compare.
float techniqueVisibility(Receiver r) { return depthTest(r.p, 0.0); }
