#include <algorithm>
#include <stdexcept>
#include <utility>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <ImfThreading.h>

#include "core/error.h"
#include "core/image.h"
#include "core/progress.h"

namespace so {

float* ChannelImage::addChannel(const std::string& name, float fill) {
    if (has(name))
        throw std::invalid_argument("image: channel \"" + printable(name) + "\" added twice");
    names_.push_back(name);
    planes_.emplace_back(pixelCount(), fill);
    return planes_.back().data();
}

bool ChannelImage::has(const std::string& name) const {
    return std::find(names_.begin(), names_.end(), name) != names_.end();
}

float* ChannelImage::channel(const std::string& name) {
    auto it = std::find(names_.begin(), names_.end(), name);
    if (it == names_.end())
        throw std::invalid_argument("image: no channel \"" + printable(name) + "\"");
    return planes_[size_t(it - names_.begin())].data();
}

const float* ChannelImage::channel(const std::string& name) const {
    return const_cast<ChannelImage*>(this)->channel(name);
}

void writeExr(const std::string& path, const ChannelImage& image, const ExrAttributes& attributes,
              int threads, Progress* progress, ExrRows rows) {
    // A whole image is the plain header (display window = data window); a band sits inside a
    // display window of the full height, so readers place its rows where they belong.
    const int fullHeight = rows.fullHeight > 0 ? rows.fullHeight : image.height();
    if (rows.rowBegin < 0 || rows.rowBegin + image.height() > fullHeight)
        throw std::invalid_argument("writeExr: rows " + std::to_string(rows.rowBegin) + ".." +
                                    std::to_string(rows.rowBegin + image.height()) +
                                    " do not fit an image " + std::to_string(fullHeight) +
                                    " rows high");
    const Imath::Box2i displayWindow({0, 0}, {image.width() - 1, fullHeight - 1});
    const Imath::Box2i dataWindow({0, rows.rowBegin},
                                  {image.width() - 1, rows.rowBegin + image.height() - 1});
    Imf::Header header(displayWindow, dataWindow);
    // ZIP at zlib's fastest level: 1 to 2% larger than OpenEXR's default level 4 and about a third
    // faster to write (docs/benchmarks.md, "The whole process"); every reader reads it the same.
    header.compression() = Imf::ZIP_COMPRESSION;
    header.zipCompressionLevel() = 1;
    for (const auto& [key, value] : attributes) header.insert(key, Imf::StringAttribute(value));
    Imf::FrameBuffer fb;
    // OpenEXR addresses a slice by absolute (x, y): the base points at where row 0 would be.
    const ptrdiff_t rowOffset =
        ptrdiff_t(rows.rowBegin) * ptrdiff_t(image.width()) * ptrdiff_t(sizeof(float));
    for (const std::string& name : image.names()) {
        header.channels().insert(name, Imf::Channel(Imf::FLOAT));
        char* base = reinterpret_cast<char*>(const_cast<float*>(image.channel(name))) - rowOffset;
        fb.insert(name, Imf::Slice(Imf::FLOAT, base, sizeof(float),
                                   sizeof(float) * size_t(image.width())));
    }
    try {
        // Compression is most of the time on large images; OpenEXR spreads it over threads and
        // still writes the blocks in order, so the bytes do not depend on the thread count.
        Imf::setGlobalThreadCount(threads > 1 ? threads : 0);
        Imf::OutputFile file(path.c_str(), header);
        file.setFrameBuffer(fb);
        const int block = 256;  // scanlines per call: enough to keep the threads busy
        for (int y = 0; y < image.height(); y += block) {
            const int n = std::min(block, image.height() - y);
            file.writePixels(n);
            if (progress) progress->advance(uint64_t(n) * uint64_t(image.width()));
        }
    } catch (const std::exception& e) {
        throwInputError(path, "", std::string("cannot write EXR: ") + printable(e.what(), 200));
    }
}

ChannelImage readExr(const std::string& path) {
    return readExrFile(path).image;
}

ExrFile readExrFile(const std::string& path) {
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        const Imath::Box2i display = file.header().displayWindow();
        ExrFile out;
        out.rows = {dw.min.y - display.min.y, display.max.y - display.min.y + 1};
        out.fullWidth = display.max.x - display.min.x + 1;
        out.columnBegin = dw.min.x - display.min.x;
        for (auto a = file.header().begin(); a != file.header().end(); ++a)
            if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&a.attribute()))
                out.attributes.emplace_back(a.name(), s->value());
        int width = dw.max.x - dw.min.x + 1, height = dw.max.y - dw.min.y + 1;
        ChannelImage image(width, height);
        Imf::FrameBuffer fb;
        for (auto it = file.header().channels().begin(); it != file.header().channels().end();
             ++it) {
            float* plane = image.addChannel(it.name());
            char* base =
                reinterpret_cast<char*>(plane) -
                (ptrdiff_t(dw.min.x) + ptrdiff_t(dw.min.y) * width) * ptrdiff_t(sizeof(float));
            fb.insert(it.name(),
                      Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * size_t(width)));
        }
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        out.image = std::move(image);
        return out;
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throwInputError(path, "", std::string("cannot read EXR: ") + printable(e.what(), 200));
    }
}

}  // namespace so
