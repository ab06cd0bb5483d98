// A multi-channel float image addressed by channel name: what the oracle and the raster path fill
// and what the EXR writer stores. Planar, row 0 at the top (docs/conventions.md).
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace so {

class ChannelImage {
  public:
    ChannelImage() = default;
    ChannelImage(int width, int height) : width_(width), height_(height) {}

    int width() const { return width_; }
    int height() const { return height_; }
    size_t pixelCount() const { return size_t(width_) * size_t(height_); }

    // Adds a channel filled with `fill`; a name already there is std::invalid_argument.
    float* addChannel(const std::string& name, float fill = 0.0f);
    bool has(const std::string& name) const;
    // A missing channel is std::invalid_argument (ask has() first where it may be absent).
    float* channel(const std::string& name);
    const float* channel(const std::string& name) const;
    const std::vector<std::string>& names() const { return names_; }
    // The planes in names() order, moved out (a large image is not copied); the image is left
    // empty.
    std::vector<std::vector<float>> releasePlanes() {
        width_ = height_ = 0;
        names_.clear();
        return std::move(planes_);
    }

  private:
    int width_ = 0, height_ = 0;
    std::vector<std::string> names_;
    std::vector<std::vector<float>> planes_;
};

class Progress;

// Where an image's rows lie in a taller one: a band of `shadow-oracle trace --tile` is stored as
// an OpenEXR data window (rows rowBegin .. rowBegin + image height - 1) inside a display window
// fullHeight rows high. fullHeight 0: the image is the whole.
struct ExrRows {
    int rowBegin = 0;
    int fullHeight = 0;
};

using ExrAttributes = std::vector<std::pair<std::string, std::string>>;

// Writes all channels as 32-bit float, ZIP-compressed scanlines, with string attributes (e.g.
// provenance). Deterministic: the same image gives the same bytes whatever `threads` (OpenEXR
// compresses blocks in parallel but writes them in order). `progress` may be null.
void writeExr(const std::string& path, const ChannelImage& image,
              const ExrAttributes& attributes = {}, int threads = 1, Progress* progress = nullptr,
              ExrRows rows = {});
// Reads every channel as float (the data window). Throws InputError on a bad file.
ChannelImage readExr(const std::string& path);

// The data window with where it lies in the display window, and the string attributes.
struct ExrFile {
    ChannelImage image;
    ExrRows rows;         // fullHeight: the display window's height
    int fullWidth = 0;    // the display window's width
    int columnBegin = 0;  // the data window's first column
    ExrAttributes attributes;
};
ExrFile readExrFile(const std::string& path);

// PNGs and textures: core/image_codec.h.

}  // namespace so
