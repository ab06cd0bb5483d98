// Fuzzes the reader of a renderer's images, `compare --image LABEL=PATH`
// (core/visibility_image.cpp): readVisibilityImage on an EXR or a PNG, and readExternalCost on the
// cost file PATH.json beside it. The input: byte 0 holds flags (bit 0: the image is a PNG, else an
// EXR; bit 1: the scene has two lights, "cone" and "fill", else one, "panel"; bit 2:
// --image-encoding srgb); bytes 1 and 2 the camera's width and height (0 is read as 1); bytes 3 and
// 4 the cost file's length L (little endian; 0: no cost file); then L bytes of cost file, then the
// image. Both are written to the scratch folder and read with the fuzz limits (at most 2^20 pixels,
// 1024 per side). Beyond "only InputError", the harness checks what compare relies on: one plane
// per light, one value per camera pixel, each in [0, 1].
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "core/visibility_image.h"
#include "tests/fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 5) return 0;
    const bool png = data[0] & 1, twoLights = data[0] & 2;
    const so::ImageEncoding encoding =
        (data[0] & 4) ? so::ImageEncoding::Srgb : so::ImageEncoding::Linear;
    const int width = data[1] ? data[1] : 1, height = data[2] ? data[2] : 1;
    const size_t costBytes = std::min(size - 5, size_t(data[3]) | (size_t(data[4]) << 8));
    const std::string_view rest(reinterpret_cast<const char*>(data) + 5, size - 5);
    const std::filesystem::path image = so::fuzz::scratchDir() / (png ? "image.png" : "image.exr");
    const std::filesystem::path cost = image.string() + ".json";
    std::error_code ec;
    std::filesystem::remove(so::fuzz::scratchDir() / "image.png.json", ec);
    std::filesystem::remove(so::fuzz::scratchDir() / "image.exr.json", ec);
    if (costBytes > 0) so::fuzz::writeFile(cost, rest.substr(0, costBytes));
    so::fuzz::writeFile(image, rest.substr(costBytes));
    std::vector<so::Light> lights(twoLights ? 2 : 1);
    lights[0].name = twoLights ? "cone" : "panel";
    if (twoLights) lights[1].name = "fill";
    so::fuzz::expectOnlyInputErrors([&] {
        const so::VisibilityImage img = so::readVisibilityImage(
            image.string(), lights, width, height, encoding, so::fuzz::fuzzLimits());
        if (img.width != width || img.height != height || img.v.size() != lights.size())
            std::abort();
        for (const std::vector<float>& plane : img.v) {
            if (plane.size() != size_t(width) * size_t(height)) std::abort();
            for (float v : plane)
                if (!(v >= 0.0f && v <= 1.0f)) std::abort();
        }
    });
    return 0;
}
