// The one translation unit that compiles tinygltf. Image decoding and writing are compiled out and
// external images are never opened: the loader installs its own do-nothing image callback, so a
// model whose textures are missing still loads (gltf_loader.cpp).
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>
