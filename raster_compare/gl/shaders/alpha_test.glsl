// The alpha test of alpha-tested materials (core/alpha_mask.h), shared by every frame that draws
// the scene (depth, moments, camera, visibility, projected shadows): it goes first among a
// program's fragment sources, and the frame calls alphaTest() first in main. Where factor times
// the texture's alpha at the fragment's uv is below the cutoff the fragment is discarded, as the
// oracle drops a hit there. GpuScene sets the uniforms per mesh and binds the mask: an R32F texture
// (the CPU's floats) through a sampler of its wrap and filter, GL_NEAREST or GL_LINEAR on one
// level (no mipmaps); a constant mask reads a 1x1 texture of 1. ALPHA_TEST_OFF (GpuScene's
// alphaDefines when no mesh is tested, and the shadow volumes, which are built from whole
// triangles) leaves the test out.
#ifdef ALPHA_TEST_OFF
void alphaTest() {}
#else
in vec2 v_uv;
uniform bool u_alphaTested;  // false: an opaque mesh, which reads nothing
uniform float u_alphaCutoff;
uniform float u_alphaFactor;
layout(binding = 8) uniform sampler2D u_alphaTexture;  // GpuScene::kAlphaTextureUnit
#ifdef SO_COUNT_WORK
uniform int u_alphaTapTexels;  // what one lookup reads: 4 bilinear, 1 nearest (R32F texels)
#endif
void alphaTest() {
    if (u_alphaTested) SO_TAP(u_alphaTapTexels, 4);
    // Level 0 explicitly: no derivatives, no mipmaps.
    if (u_alphaTested && u_alphaFactor * textureLod(u_alphaTexture, v_uv, 0.0).r < u_alphaCutoff)
        discard;
}
#endif
