// Shadow volumes, first frame only: one per volume face over a pixel, summed by blending, for the
// largest count a pixel's stencil must hold.
layout(location = 0) out float o_count;
void main() { o_count = 1.0; }
