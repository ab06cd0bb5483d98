// The EXR contract (docs/exr-channels.md) as OpenImageIO sees it: oracle.exr and raster.exr are
// written with OpenEXR's API (core/exr_io.cpp), and users read them with OpenImageIO tools (idiff,
// oiiotool) or libraries. Written one way, read both ways: the same channel names, all 32-bit
// float, the same values bit for bit, and the provenance attributes. Its own binary: it links
// OpenImageIO, which the other test binaries load only through the image module.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include "core/image.h"

namespace so {
namespace {

namespace fs = std::filesystem;

TEST(ExrContract, OpenImageIOReadsWhatOpenExrWrote) {
    const int w = 7, h = 5;
    ChannelImage img(w, h);
    const std::vector<std::string> names = {"A",       "P.X",         "Z",          "id.mesh",
                                            "key.V",   "key.cos",     "key.stderr", "key.spp",
                                            "panel.V", "key.occ_dist"};
    for (size_t c = 0; c < names.size(); ++c) {
        float* p = img.addChannel(names[c]);
        for (int i = 0; i < w * h; ++i) p[i] = float(c) + 0.125f * float(i) - 1.0f;
    }
    img.channel("Z")[3] = std::numeric_limits<float>::infinity();
    const fs::path file =
        fs::temp_directory_path() / ("so_exr_oiio_" + std::to_string(::getpid()) + ".exr");
    writeExr(file.string(), img, {{"shadowOracle/sceneHash", "abc123"}});

    auto in = OIIO::ImageInput::open(file.string());
    ASSERT_TRUE(in) << OIIO::geterror();
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.width, w);
    EXPECT_EQ(spec.height, h);
    ASSERT_EQ(size_t(spec.nchannels), names.size());
    std::set<std::string> seen;
    for (int c = 0; c < spec.nchannels; ++c) {
        seen.insert(spec.channelnames[size_t(c)]);
        EXPECT_EQ(spec.channelformat(c), OIIO::TypeDesc::FLOAT) << spec.channelnames[size_t(c)];
    }
    EXPECT_EQ(seen, std::set<std::string>(names.begin(), names.end()));
    EXPECT_EQ(spec.get_string_attribute("shadowOracle/sceneHash"), "abc123");
    EXPECT_EQ(spec.get_string_attribute("compression"), "zip");

    std::vector<float> pixels(size_t(w) * size_t(h) * size_t(spec.nchannels));
    ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
    in->close();
    // OpenEXR's own reader, the same file.
    const ChannelImage back = readExr(file.string());
    for (int c = 0; c < spec.nchannels; ++c) {
        const std::string& name = spec.channelnames[size_t(c)];
        const float* expected = back.channel(name);
        for (int i = 0; i < w * h; ++i) {
            const float v = pixels[size_t(i) * size_t(spec.nchannels) + size_t(c)];
            ASSERT_EQ(std::memcmp(&v, &expected[i], sizeof v), 0) << name << " pixel " << i;
            ASSERT_EQ(std::memcmp(&v, &img.channel(name)[i], sizeof v), 0) << name << " " << i;
        }
    }
    fs::remove(file);
}

}  // namespace
}  // namespace so
