#include "core/visibility_image.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include "core/channels.h"
#include "core/error.h"
#include "core/gbuffer.h"
#include "core/image_codec.h"
#include "core/json_reader.h"
#include "core/read_file.h"

namespace so {

namespace {

std::string sizeText(int w, int h) {
    return std::to_string(w) + " x " + std::to_string(h);
}

void checkSize(const std::string& path, int w, int h, int width, int height) {
    if (w != width || h != height)
        throwInputError(
            path, "size",
            "image is " + sizeText(w, h) + ", the camera's is " + sizeText(width, height));
}

// The channel names to read, one per light: NAME.V, or for one light a lone V, Y or R.
std::vector<std::string> exrChannelsFor(const std::string& path, const Imf::ChannelList& list,
                                        const std::vector<Light>& lights) {
    const auto has = [&](const std::string& name) { return list.findChannel(name) != nullptr; };
    std::vector<std::string> names;
    for (const Light& l : lights) {
        const std::string name = channels::lightChannel(l.name, channels::kVisibility);
        if (has(name)) {
            names.push_back(name);
            continue;
        }
        if (lights.size() == 1)
            for (const char* single : {"V", "Y", "R"})
                if (has(single)) {
                    names.push_back(single);
                    break;
                }
        if (names.size() < size_t(&l - lights.data()) + 1)
            throwInputError(path, name,
                            "missing: light \"" + l.name + "\" has no channel" +
                                (lights.size() == 1 ? " (nor V, Y or R)" : ""));
    }
    return names;
}

VisibilityImage readExrVisibility(const std::string& path, const std::vector<Light>& lights,
                                  int width, int height, const LoadLimits& limits) {
    checkExrHeader(path, limits);
    VisibilityImage img;
    img.path = path;
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
        checkSize(path, w, h, width, height);
        const std::vector<std::string> names =
            exrChannelsFor(path, file.header().channels(), lights);
        img.width = w, img.height = h;
        img.v.assign(names.size(), std::vector<float>(size_t(w) * size_t(h), 0.0f));
        Imf::FrameBuffer fb;
        for (size_t k = 0; k < names.size(); ++k) {
            // OpenEXR addresses a slice by absolute (x, y); half and uint convert to float.
            char* base = reinterpret_cast<char*>(img.v[k].data()) -
                         (ptrdiff_t(dw.min.x) + ptrdiff_t(dw.min.y) * ptrdiff_t(w)) *
                             ptrdiff_t(sizeof(float));
            fb.insert(names[k],
                      Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * size_t(w)));
        }
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        for (size_t k = 0; k < names.size(); ++k)
            checkVisibilityValues(path, names[k], img.v[k], w);
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throwInputError(path, "", std::string("cannot read EXR: ") + printable(e.what(), 200));
    }
    return img;
}

float srgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

VisibilityImage readPngVisibility(const std::string& path, const std::vector<Light>& lights,
                                  int width, int height, ImageEncoding encoding,
                                  const LoadLimits& limits) {
    if (lights.size() != 1)
        throwInputError(path, "channels",
                        "a grey image holds one light's V, the scene has " +
                            std::to_string(lights.size()) + " (give an EXR with NAME.V each)");
    const TextureRgba t =
        readTextureRgba(path, limits.maxImageSide, limits.maxImageSide, limits.maxImagePixels);
    if (t.fileChannels != 1)
        throwInputError(path, "channels",
                        std::to_string(t.fileChannels) + " channels: expected one grey channel");
    checkSize(path, t.width, t.height, width, height);
    VisibilityImage img;
    img.path = path;
    img.width = t.width, img.height = t.height;
    img.v.assign(1, std::vector<float>(size_t(t.width) * size_t(t.height)));
    for (size_t i = 0; i < img.v[0].size(); ++i) {
        const float code = t.rgba[4 * i];  // code / max code, as OpenImageIO reads it
        img.v[0][i] = encoding == ImageEncoding::Srgb ? srgbToLinear(code) : code;
    }
    checkVisibilityValues(path, "V", img.v[0], t.width);
    return img;
}

std::optional<double> costNumber(const nlohmann::json& j, const std::string& key,
                                 const JsonReader& r) {
    const nlohmann::json* v = JsonReader::find(j, key);
    if (!v) return std::nullopt;
    return r.numberAtLeast(*v, key, 0.0);
}

}  // namespace

void checkVisibilityValues(const std::string& path, const std::string& channel,
                           std::vector<float>& v, int width) {
    for (size_t i = 0; i < v.size(); ++i) {
        const float x = v[i];
        if (std::isfinite(x) && x >= -kVisibilityTolerance && x <= 1.0f + kVisibilityTolerance) {
            v[i] = std::clamp(x, 0.0f, 1.0f);
            continue;
        }
        throwInputError(path, channel,
                        (std::isfinite(x) ? "value " + std::to_string(x) + " outside [0, 1]"
                                          : std::string("non-finite value")) +
                            " at pixel (" + std::to_string(i % size_t(width)) + ", " +
                            std::to_string(i / size_t(width)) + ")");
    }
}

ImageEncoding parseImageEncoding(const std::string& text, const std::string& file,
                                 const std::string& field) {
    if (text == "linear") return ImageEncoding::Linear;
    if (text == "srgb") return ImageEncoding::Srgb;
    throwInputError(file, field,
                    "unknown encoding \"" + printable(text, 40) + "\" (valid: linear, srgb)");
}

std::optional<ExternalCost> readExternalCost(const std::string& jsonPath) {
    std::error_code ec;
    if (!std::filesystem::exists(jsonPath, ec)) return std::nullopt;
    const std::string text = readFileCapped(jsonPath, jsonPath, uint64_t(1) << 20);
    const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
    if (j.is_discarded()) throwInputError(jsonPath, "", "invalid JSON");
    const JsonReader r(jsonPath);
    r.checkKeys(j, "", {"renderer", "frame_ms", "shadow_ms", "memory_bytes", "params"});
    ExternalCost c;
    if (const nlohmann::json* renderer = JsonReader::find(j, "renderer"))
        c.renderer = printable(r.string(*renderer, "renderer"), 200);
    c.frameMs = costNumber(j, "frame_ms", r);
    c.shadowMs = costNumber(j, "shadow_ms", r);
    if (const auto m = costNumber(j, "memory_bytes", r)) {
        if (*m > 0x1p62)
            r.fail("memory_bytes", "must be in [0, 2^62], got " + JsonReader::numberText(*m));
        c.memoryBytes = uint64_t(*m);
    }
    if (j.contains("params")) {
        r.requireObject(j["params"], "params");
        for (const auto& [key, value] : j["params"].items()) {
            if (!(value.is_number() || value.is_string() || value.is_boolean()))
                r.fail("params." + printable(key, 40),
                       "expected a number, a string or true or false, got " +
                           JsonReader::typeName(value));
            if (value.is_number()) r.number(value, "params." + printable(key, 40));
            if (key.empty() || key.size() > 64)
                throwInputError(jsonPath, "params", "names are 1 to 64 characters");
        }
        c.params = j["params"];
    }
    return c;
}

VisibilityImage readVisibilityImage(const std::string& path, const std::vector<Light>& lights,
                                    int width, int height, ImageEncoding encoding,
                                    const LoadLimits& limits) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throwInputError(path, "", "no such file (or not a regular file)");
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
    VisibilityImage img = ext == ".exr"
                              ? readExrVisibility(path, lights, width, height, limits)
                              : readPngVisibility(path, lights, width, height, encoding, limits);
    img.cost = readExternalCost(path + ".json");
    return img;
}

}  // namespace so
