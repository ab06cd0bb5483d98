// A renderer's shadow visibility image, the input of `compare --image LABEL=PATH`
// (docs/external.md, "Images in"): per light of the scene a plane of V in [0, 1], row 0 at the
// top, and the optional cost file PATH.json beside it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/scene.h"

namespace so {

// How an integer PNG's codes become V: `Linear` V = code / max code; `Srgb` the sRGB transfer
// function decoded first. An EXR is linear whatever this says.
enum class ImageEncoding { Linear, Srgb };
// "linear" or "srgb"; throws InputError naming `file` and `field` otherwise.
ImageEncoding parseImageEncoding(const std::string& text, const std::string& file,
                                 const std::string& field);

// Values this far outside [0, 1] are clamped (a renderer's rounding); farther is an error.
inline constexpr float kVisibilityTolerance = 1e-3f;

// Every value finite and within [0, 1] up to kVisibilityTolerance, then clamped; otherwise an
// InputError naming `file`, `channel` and the pixel. What every image of V goes through, read from
// a file or given in memory (the C++ and Python APIs).
void checkVisibilityValues(const std::string& file, const std::string& channel,
                           std::vector<float>& v, int width);

// PATH.json: what the image cost to make, each entry optional (absent: unknown, not zero).
struct ExternalCost {
    std::string renderer;
    std::optional<double> frameMs, shadowMs;
    std::optional<uint64_t> memoryBytes;
    nlohmann::json params = nlohmann::json::object();  // name: number, string or bool
};

struct VisibilityImage {
    std::string path;
    int width = 0, height = 0;
    std::vector<std::vector<float>> v;  // per light, in the scene's order; width * height each
    std::optional<ExternalCost> cost;   // PATH.json, when present
};

// Reads and validates the image for `lights` at width x height: an EXR with NAME.V per light (or
// one of V, Y, R for a scene with one light), or an 8 or 16-bit grey PNG (one light). Throws
// InputError ("FILE: FIELD: why") for an unreadable file, a wrong size, a missing channel, a
// non-finite value or one outside [0, 1] beyond kVisibilityTolerance, and for a malformed cost
// file. Reads at most `limits.maxImagePixels` pixels.
VisibilityImage readVisibilityImage(const std::string& path, const std::vector<Light>& lights,
                                    int width, int height, ImageEncoding encoding,
                                    const LoadLimits& limits = {});

// PATH.json's content, or none when the file does not exist; InputError naming the file and
// field for anything else than the documented keys and types.
std::optional<ExternalCost> readExternalCost(const std::string& jsonPath);

}  // namespace so
