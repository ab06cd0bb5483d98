#include "core/gbuffer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <utility>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include "core/channels.h"
#include "core/error.h"

namespace so {

namespace {

namespace ch = channels;

// The checks on values, after the pixels are in: one line naming the channel and the pixel.
void checkPixels(const GBuffer& g) {
    const auto where = [&](size_t i) {
        return " at pixel (" + std::to_string(i % size_t(g.width)) + ", " +
               std::to_string(i / size_t(g.width)) + ")";
    };
    const std::pair<const char*, const std::vector<float>*> required[] = {
        {ch::kPX, &g.wsPX}, {ch::kPY, &g.wsPY}, {ch::kPZ, &g.wsPZ},
        {ch::kNX, &g.wsNX}, {ch::kNY, &g.wsNY}, {ch::kNZ, &g.wsNZ}};
    for (size_t i = 0; i < g.pixelCount(); ++i) {
        if (!std::isfinite(g.coverage[i]))
            throwInputError(g.path, g.coverageChannel, "not a finite number" + where(i));
        if (!g.covered(i)) continue;
        for (const auto& [name, plane] : required)
            if (!std::isfinite((*plane)[i]))
                throwInputError(g.path, name,
                                "not a finite number" + where(i) + ", which is covered");
        if (g.wsNX[i] == 0.0f && g.wsNY[i] == 0.0f && g.wsNZ[i] == 0.0f)
            throwInputError(g.path, ch::kNX, "zero normal (N.X, N.Y, N.Z all 0)" + where(i));
    }
}

// The header walked before OpenEXR sees the file, consuming bytes exactly as OpenEXR 3.1's
// Header::readFrom does: it allocates attributes at sizes the file declares (a 1 KB file can ask
// for gigabytes: found by fuzz_gbuffer) and the chunk table at the data window's size, before any
// check of ours. Typed attributes are read at their fixed size whatever the declared one (so this
// walk follows them the same way), a chlist up to its empty name, a preview by its own width and
// height; everything else by the declared size. Every length must fit in what is left of the file;
// the file must be single-part and flat, and the data window, equal to the display window, must
// fit the limits. Layout: magic, version, then (name NUL, type NUL, int32 size, value) until an
// empty name.

// The data window's size within the limits, as a one-line error naming it.
void checkWindowSize(const std::string& path, int64_t w, int64_t h, const LoadLimits& limits) {
    if (w < 1 || h < 1 || w > limits.maxImageSide || h > limits.maxImageSide ||
        uint64_t(w) * uint64_t(h) > limits.maxImagePixels)
        throwInputError(path, "dataWindow",
                        "image of " + std::to_string(w) + " x " + std::to_string(h) +
                            " pixels is empty or too large (at most " +
                            std::to_string(limits.maxImageSide) + " per side and " +
                            std::to_string(limits.maxImagePixels) + " pixels)");
}

}  // namespace

void checkExrHeader(const std::string& path, const LoadLimits& limits) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throwInputError(path, "", "cannot open");
    in.seekg(0, std::ios::end);
    const int64_t fileSize = int64_t(in.tellg());
    in.seekg(0);
    const auto left = [&] { return fileSize - int64_t(in.tellg()); };
    const auto readInt = [&](const std::string& what) {
        unsigned char b[4];
        if (!in.read(reinterpret_cast<char*>(b), 4))
            throwInputError(path, what, "the file ends inside the header");
        return int32_t(uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 |
                       uint32_t(b[3]) << 24);
    };
    const auto readName = [&](const std::string& what) {
        std::string name;
        for (char c; in.get(c) && c != '\0';) {
            name += c;
            if (name.size() > 255) throwInputError(path, what, "a name longer than 255 bytes");
        }
        if (!in) throwInputError(path, what, "the file ends inside the header");
        return name;
    };
    const auto skip = [&](const std::string& what, int64_t bytes) {
        if (bytes < 0 || bytes > left())
            throwInputError(path, what,
                            "declares " + std::to_string(bytes) + " bytes, more than the " +
                                std::to_string(left()) + " left in the file");
        in.seekg(bytes, std::ios::cur);
    };
    if (readInt("magic") != 20000630) throwInputError(path, "magic", "not an OpenEXR file");
    const int32_t version = readInt("version");
    if (version & 0x1800)
        throwInputError(path, "version",
                        "a multi-part or deep file; give a single-part scanline or tiled image");
    static const std::pair<const char*, int> kFixed[] = {{"box2i", 16},
                                                         {"box2f", 16},
                                                         {"chromaticities", 32},
                                                         {"compression", 1},
                                                         {"deepImageState", 1},
                                                         {"double", 8},
                                                         {"envmap", 1},
                                                         {"float", 4},
                                                         {"int", 4},
                                                         {"keycode", 28},
                                                         {"lineOrder", 1},
                                                         {"m33f", 36},
                                                         {"m33d", 72},
                                                         {"m44f", 64},
                                                         {"m44d", 128},
                                                         {"rational", 8},
                                                         {"timecode", 8},
                                                         {"tiledesc", 9},
                                                         {"v2i", 8},
                                                         {"v2f", 8},
                                                         {"v2d", 16},
                                                         {"v3i", 12},
                                                         {"v3f", 12},
                                                         {"v3d", 24}};
    int32_t box[2][4] = {};
    bool found[2] = {false, false};
    for (;;) {
        const std::string name = readName("header");
        if (name.empty()) break;
        const std::string field = printable(name, 40);
        const std::string type = readName(field);
        const int32_t size = readInt(field);
        const int w = name == "dataWindow" ? 0 : name == "displayWindow" ? 1 : -1;
        int fixed = -1;
        for (const auto& [t, n] : kFixed)
            if (type == t) fixed = n;
        if (w >= 0 && type == "box2i") {
            for (int k = 0; k < 4; ++k) box[w][k] = readInt(field);
            found[w] = true;
        } else if (fixed >= 0) {
            skip(field, fixed);
        } else if (type == "chlist") {
            while (!readName(field).empty()) skip(field, 16);
        } else if (type == "preview") {
            const uint64_t pw = uint32_t(readInt(field)), ph = uint32_t(readInt(field));
            const uint64_t pixels = pw * ph;  // below 2^64; 4 bytes each could overflow
            if (pixels > uint64_t(std::max<int64_t>(left(), 0)) / 4)
                throwInputError(path, field,
                                "a preview of " + std::to_string(pw) + " x " + std::to_string(ph) +
                                    " pixels, more than the " + std::to_string(left()) +
                                    " bytes left in the file");
            skip(field, int64_t(4 * pixels));
        } else if (type == "stringvector") {
            skip(field, 0);
            for (int64_t read = 0; read < size;) {
                const int32_t n = readInt(field);
                skip(field, n);
                read += 4 + int64_t(n);
            }
        } else if (type == "idmanifest") {
            readInt(field);  // the uncompressed size: allocated only when decompressed
            skip(field, readInt(field));
        } else {
            skip(field, size);  // string, floatvector, and unknown types (opaque)
        }
    }
    if (!found[0] || !found[1])
        throwInputError(path, found[0] ? "displayWindow" : "dataWindow", "missing");
    if (!std::equal(box[0], box[0] + 4, box[1]))
        throwInputError(path, "dataWindow",
                        "differs from the display window (a cropped image or one band of a "
                        "tiled trace); give the whole image");
    checkWindowSize(path, int64_t(box[0][2]) - int64_t(box[0][0]) + 1,
                    int64_t(box[0][3]) - int64_t(box[0][1]) + 1, limits);
}

GBuffer readGBuffer(const std::string& path, const LoadLimits& limits) {
    GBuffer g;
    g.path = path;
    checkExrHeader(path, limits);
    try {
        Imf::InputFile file(path.c_str());
        const Imf::Header& header = file.header();
        const Imath::Box2i dw = header.dataWindow(), display = header.displayWindow();
        if (dw != display)
            throwInputError(path, "dataWindow",
                            "differs from the display window (a cropped image or one band of a "
                            "tiled trace); give the whole image");
        const int64_t w = int64_t(dw.max.x) - int64_t(dw.min.x) + 1;
        const int64_t h = int64_t(dw.max.y) - int64_t(dw.min.y) + 1;
        checkWindowSize(path, w, h, limits);  // as the header walk read it, now as OpenEXR does
        g.width = int(w);
        g.height = int(h);
        const Imf::ChannelList& list = header.channels();
        const auto has = [&](const char* name) { return list.findChannel(name) != nullptr; };
        for (const char* name : {ch::kPX, ch::kPY, ch::kPZ, ch::kNX, ch::kNY, ch::kNZ})
            if (!has(name)) throwInputError(path, name, "missing channel");
        if (has(ch::kHit))
            g.coverageChannel = ch::kHit;
        else if (has(ch::kCoverage))
            g.coverageChannel = ch::kCoverage;
        else
            throwInputError(path, ch::kHit, "missing coverage channel (A or coverage)");
        const char* replay[] = {ch::kMeshId, ch::kPrimId, ch::kBaryU, ch::kBaryV};
        int replayPresent = 0;
        for (const char* name : replay) replayPresent += has(name);
        // oracle.exr and raster.exr carry the ids without barycentrics: those are snapped. A
        // barycentric channel without the other three is a broken replay, refused.
        if ((has(ch::kBaryU) || has(ch::kBaryV)) && replayPresent != 4)
            for (const char* name : replay)
                if (!has(name))
                    throwInputError(path, name,
                                    "missing: the exact-replay channels id.mesh, id.prim, bary.u "
                                    "and bary.v come all four together");

        std::vector<std::pair<std::string, std::vector<float>*>> planes = {
            {g.coverageChannel, &g.coverage},
            {ch::kPX, &g.wsPX},
            {ch::kPY, &g.wsPY},
            {ch::kPZ, &g.wsPZ},
            {ch::kNX, &g.wsNX},
            {ch::kNY, &g.wsNY},
            {ch::kNZ, &g.wsNZ}};
        if (replayPresent == 4) {
            planes.emplace_back(ch::kMeshId, &g.meshId);
            planes.emplace_back(ch::kPrimId, &g.primId);
            planes.emplace_back(ch::kBaryU, &g.baryU);
            planes.emplace_back(ch::kBaryV, &g.baryV);
        }
        if (has(ch::kDepth)) planes.emplace_back(ch::kDepth, &g.depth);
        Imf::FrameBuffer fb;
        for (auto& [name, plane] : planes) {
            plane->assign(g.pixelCount(), 0.0f);
            // OpenEXR addresses a slice by absolute (x, y): the base points at where (0, 0) would
            // be. Channels stored as half or uint are converted to float.
            char* base = reinterpret_cast<char*>(plane->data()) -
                         (ptrdiff_t(dw.min.x) + ptrdiff_t(dw.min.y) * ptrdiff_t(w)) *
                             ptrdiff_t(sizeof(float));
            fb.insert(name, Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * size_t(w)));
        }
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throwInputError(path, "", std::string("cannot read EXR: ") + printable(e.what(), 200));
    }
    checkPixels(g);
    return g;
}

}  // namespace so
