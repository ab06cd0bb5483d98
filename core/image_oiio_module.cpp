// The image module: every PNG/texture encode and decode of the project, through OpenImageIO. Built
// as a MODULE library that core/image_module.cpp dlopen()s on the first image call, because linking
// OpenImageIO into a program costs ~250 ms of dynamic linking at every start (docs/benchmarks.md)
// and most commands (`--version`, `gate`, `index`) never touch an image. It links nothing of ours:
// the caller has already turned floats into the bytes to store, so the pixels written are decided
// in one place (core/image_codec.cpp). Exports one C function table (core/image_module_abi.h);
// nothing thrown here may escape it.
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <mutex>
#include <string>
#include <vector>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/oiioversion.h>

#include "core/image_module_abi.h"

namespace {

using OIIO::ImageInput;
using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

// OpenImageIO's messages may span lines; ours are one line.
int fail(char* error, size_t errorSize, std::string message) {
    if (message.empty()) message = "unknown OpenImageIO error";
    std::replace(message.begin(), message.end(), '\n', ' ');
    if (errorSize > 0) std::snprintf(error, errorSize, "%s", message.c_str());
    return 1;
}

int writePng8(const char* path, SoImageByteSink sink, void* sinkData, int width, int height,
              int channels, const unsigned char* pixels, int compressionLevel, int pngFilter,
              char* error, size_t errorSize) try {
    // In memory the bytes go to the vector, and the name is only for messages.
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput memory(bytes);
    OIIO::Filesystem::IOProxy* proxy = path ? nullptr : &memory;
    const std::string name = path ? path : "memory.png";
    // By format name: a PNG whatever the file's extension, as before.
    std::unique_ptr<ImageOutput> out = ImageOutput::create("png", proxy);
    if (!out) return fail(error, errorSize, OIIO::geterror());
    ImageSpec spec(width, height, channels, TypeDesc::UINT8);
    // Tags the file sRGB (an sRGB chunk), as the bytes are sRGB-encoded.
    spec.attribute("oiio:ColorSpace", "sRGB");
    spec.attribute("png:compressionLevel", compressionLevel);
    spec.attribute("png:filter", pngFilter);
    // The bytes are stored as given: OpenImageIO would otherwise take colours as premultiplied by
    // an alpha channel and divide them by it.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    if (!out->open(name, spec) || !out->write_image(TypeDesc::UINT8, pixels) || !out->close())
        return fail(error, errorSize, out->geterror());
    if (!path) sink(sinkData, bytes.data(), bytes.size());
    return 0;
} catch (const std::exception& e) {
    return fail(error, errorSize, e.what());
} catch (...) {
    return fail(error, errorSize, "unknown exception");
}

// Why a file is refused before its pixels are read, or "" when it is not.
std::string refusal(const ImageSpec& spec, int maxWidth, int maxHeight, uint64_t maxPixels) {
    if (spec.deep) return "deep images are not supported";
    if (spec.depth > 1) return "volume images are not supported";
    if (spec.width <= 0 || spec.height <= 0) return "the image has no pixels";
    if (spec.nchannels < 1 || spec.nchannels > 4)
        return "has " + std::to_string(spec.nchannels) + " channels; 1 to 4 are supported";
    const std::string size = std::to_string(spec.width) + " x " + std::to_string(spec.height);
    if (spec.width > maxWidth || spec.height > maxHeight)
        return "is " + size + " pixels, more than the limit of " + std::to_string(maxWidth) +
               " x " + std::to_string(maxHeight);
    if (uint64_t(spec.width) * uint64_t(spec.height) > maxPixels)
        return "is " + size + " pixels, more than the limit of " + std::to_string(maxPixels) +
               " pixels";
    return "";
}

// libpng, under OpenImageIO 2.4's PNG reader, prints a broken file's error to stderr ("libpng
// error: ...") before OpenImageIO reports it: stderr is held on /dev/null while an image is read,
// so that a broken texture gives the project's one-line error only. Reads happen while a scene
// loads, before any progress output; the mutex keeps two reads from restoring each other's stderr.
class QuietStderr {
  public:
    QuietStderr() : lock_(mutex()) {
        std::fflush(stderr);
        saved_ = ::dup(2);
        const int null = ::open("/dev/null", O_WRONLY);
        if (saved_ >= 0 && null >= 0) ::dup2(null, 2);
        if (null >= 0) ::close(null);
    }
    ~QuietStderr() {
        std::fflush(stderr);
        if (saved_ >= 0) {
            ::dup2(saved_, 2);
            ::close(saved_);
        }
    }
    QuietStderr(const QuietStderr&) = delete;
    QuietStderr& operator=(const QuietStderr&) = delete;

  private:
    static std::mutex& mutex() {
        static std::mutex m;
        return m;
    }
    std::lock_guard<std::mutex> lock_;
    int saved_ = -1;
};

// Reads `name` (a path, or with `proxy` a name whose extension picks the format).
int readFrom(const std::string& name, OIIO::Filesystem::IOProxy* proxy, int maxWidth, int maxHeight,
             uint64_t maxPixels, SoImageRgbaAllocator allocate, void* allocatorData, int* channels,
             char* error, size_t errorSize) {
    // PNG's alpha is unassociated; OpenImageIO would premultiply the colours by it unless told.
    ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    // OpenImageIO 2.4.7 ignores open()'s own proxy argument ("Could not open file"); the proxy
    // given through the configuration is honoured.
    if (proxy) config.attribute("oiio:ioproxy", TypeDesc::PTR, &proxy);
    const QuietStderr quiet;
    std::unique_ptr<ImageInput> in = ImageInput::open(name, &config);
    if (!in) return fail(error, errorSize, OIIO::geterror());
    const ImageSpec spec = in->spec();
    if (std::string why = refusal(spec, maxWidth, maxHeight, maxPixels); !why.empty())
        return fail(error, errorSize, why);
    float* rgba = allocate(allocatorData, spec.width, spec.height);
    if (!rgba) return fail(error, errorSize, "no memory for the pixels");
    // Straight into the caller's 4-float pixels; the strides skip the channels the file lacks.
    const OIIO::stride_t pixelStride = 4 * sizeof(float);
    if (!in->read_image(0, 0, 0, spec.nchannels, TypeDesc::FLOAT, rgba, pixelStride,
                        pixelStride * spec.width))
        return fail(error, errorSize, in->geterror());
    *channels = spec.nchannels;
    return 0;
}

int readPixels(const char* path, int maxWidth, int maxHeight, uint64_t maxPixels,
               SoImageRgbaAllocator allocate, void* allocatorData, int* channels, char* error,
               size_t errorSize) try {
    return readFrom(path, nullptr, maxWidth, maxHeight, maxPixels, allocate, allocatorData,
                    channels, error, errorSize);
} catch (const std::exception& e) {
    return fail(error, errorSize, e.what());
} catch (...) {
    return fail(error, errorSize, "unknown exception");
}

int readPixelsFromMemory(const unsigned char* bytes, size_t size, int maxWidth, int maxHeight,
                         uint64_t maxPixels, SoImageRgbaAllocator allocate, void* allocatorData,
                         int* channels, char* error, size_t errorSize) try {
    static const unsigned char kPng[] = {0x89, 'P', 'N', 'G'}, kJpeg[] = {0xFF, 0xD8, 0xFF};
    const char* name = size >= 4 && std::equal(kPng, kPng + 4, bytes)     ? "memory.png"
                       : size >= 3 && std::equal(kJpeg, kJpeg + 3, bytes) ? "memory.jpg"
                                                                          : nullptr;
    if (!name) return fail(error, errorSize, "not a PNG, JPEG or WebP file");
    OIIO::Filesystem::IOMemReader memory(bytes, size);
    return readFrom(name, &memory, maxWidth, maxHeight, maxPixels, allocate, allocatorData,
                    channels, error, errorSize);
} catch (const std::exception& e) {
    return fail(error, errorSize, e.what());
} catch (...) {
    return fail(error, errorSize, "unknown exception");
}

const SoImageModule kModule = {
    SO_IMAGE_MODULE_ABI_VERSION, OIIO_VERSION_STRING, writePng8, readPixels, readPixelsFromMemory,
};

}  // namespace

extern "C" __attribute__((visibility("default"))) const SoImageModule* so_image_module_v1() {
    return &kModule;
}
