#include "core/gbuffer.h"

#include <cmath>
#include <cstdint>
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

}  // namespace

GBuffer readGBuffer(const std::string& path, const LoadLimits& limits) {
    GBuffer g;
    g.path = path;
    try {
        Imf::InputFile file(path.c_str());
        const Imf::Header& header = file.header();
        const Imath::Box2i dw = header.dataWindow(), display = header.displayWindow();
        if (dw != display)
            throwInputError(path, "dataWindow",
                            "differs from the display window (a cropped image or a band of trace "
                            "--tile); give the whole image");
        const int64_t w = int64_t(dw.max.x) - int64_t(dw.min.x) + 1;
        const int64_t h = int64_t(dw.max.y) - int64_t(dw.min.y) + 1;
        if (w < 1 || h < 1 || w > limits.maxImageSide || h > limits.maxImageSide ||
            uint64_t(w) * uint64_t(h) > limits.maxImagePixels)
            throwInputError(path, "dataWindow",
                            "image of " + std::to_string(w) + " x " + std::to_string(h) +
                                " pixels is empty or too large (at most " +
                                std::to_string(limits.maxImageSide) + " per side and " +
                                std::to_string(limits.maxImagePixels) + " pixels)");
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
