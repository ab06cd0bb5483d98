// core/image_codec.h through the OpenImageIO module: PNG round trips with exact 8-bit values,
// textures of 1 to 4 channels, and broken, foreign and oversized files (an error naming the file,
// never a crash), plus the module's lazy loading and its error when missing.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image_codec.h"
#include "core/image_module.h"

namespace so {
namespace {

namespace fs = std::filesystem;

fs::path tempDir() {
    const fs::path dir =
        fs::temp_directory_path() / ("so_image_codec_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir;
}

std::vector<float> randomRgb(int width, int height, bool grey, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-0.1f, 1.1f);  // beyond [0,1] too: clamped
    std::vector<float> rgb(size_t(width) * size_t(height) * 3);
    for (size_t i = 0; i < rgb.size(); i += 3) {
        rgb[i] = u(rng);
        rgb[i + 1] = grey ? rgb[i] : u(rng);
        rgb[i + 2] = grey ? rgb[i] : u(rng);
    }
    return rgb;
}

std::vector<unsigned char> readBytes(const fs::path& path) {
    std::ifstream f(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

void writeBytes(const fs::path& path, const std::vector<unsigned char>& bytes) {
    std::ofstream f(path, std::ios::binary);
    f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// The IHDR colour type: 0 grey, 2 RGB, 3 palette, 4 grey+alpha, 6 RGBA.
int pngColourType(const std::vector<unsigned char>& png) {
    EXPECT_GT(png.size(), 26u);
    EXPECT_EQ(std::string(png.begin() + 1, png.begin() + 4), "PNG");
    return png.size() > 25 ? png[25] : -1;
}

// Every decoded value is exactly the toSrgb8 code of the input; grey files give R = G = B.
void expectSamePixels(const TextureRgba& t, int width, int height, const std::vector<float>& rgb) {
    ASSERT_EQ(t.width, width);
    ASSERT_EQ(t.height, height);
    ASSERT_EQ(t.rgba.size(), size_t(width) * size_t(height) * 4);
    for (size_t i = 0; i < size_t(width) * size_t(height); ++i) {
        for (size_t k = 0; k < 3; ++k)
            ASSERT_EQ(std::lround(t.rgba[4 * i + k] * 255.0f), toSrgb8(rgb[3 * i + k]))
                << "pixel " << i << " channel " << k;
        ASSERT_EQ(t.rgba[4 * i + 3], 1.0f);
    }
}

TEST(ImageCodec, PngRoundTripRgbIsExact) {
    const fs::path path = tempDir() / "rgb.png";
    const std::vector<float> rgb = randomRgb(37, 23, false, 1);
    writePngRgb(path.string(), 37, 23, rgb);
    EXPECT_EQ(pngColourType(readBytes(path)), 2);
    const TextureRgba t = readTextureRgba(path.string());
    EXPECT_EQ(t.fileChannels, 3);
    expectSamePixels(t, 37, 23, rgb);
}

TEST(ImageCodec, PngRoundTripGreyIsOneChannelAndExact) {
    const fs::path path = tempDir() / "grey.png";
    const std::vector<float> rgb = randomRgb(19, 41, true, 2);
    writePngRgb(path.string(), 19, 41, rgb);
    EXPECT_EQ(pngColourType(readBytes(path)), 0);
    const TextureRgba t = readTextureRgba(path.string());
    EXPECT_EQ(t.fileChannels, 1);
    expectSamePixels(t, 19, 41, rgb);
}

TEST(ImageCodec, EncodedPngDecodesToTheSamePixels) {
    for (const bool grey : {false, true}) {
        const std::vector<float> rgb = randomRgb(30, 20, grey, 3);
        const std::vector<unsigned char> png = encodePngRgb(30, 20, rgb);
        EXPECT_EQ(pngColourType(png), grey ? 0 : 2);
        const fs::path path = tempDir() / (grey ? "encoded_grey.png" : "encoded_rgb.png");
        writeBytes(path, png);
        expectSamePixels(readTextureRgba(path.string()), 30, 20, rgb);
    }
}

// The SUB filter wraps modulo 256 (0 after 255 and back); one-pixel rows have nothing to its left.
TEST(ImageCodec, PngEdgeValuesAndSizesRoundTripAndAreDeterministic) {
    for (const bool grey : {true, false}) {
        for (const auto& [width, height] : {std::pair{1, 1}, std::pair{1, 7}, std::pair{9, 1}}) {
            std::vector<float> rgb(size_t(width) * size_t(height) * 3);
            for (size_t i = 0; i < rgb.size(); ++i)
                rgb[i] = grey ? ((i / 3) % 2 == 0 ? 1.0f : 0.0f)
                              : (i % 3 == 0 ? 1.0f : 0.3f * float(i % 3));
            if (grey)
                for (size_t i = 0; i < rgb.size(); i += 3) rgb[i + 1] = rgb[i + 2] = rgb[i];
            const std::vector<unsigned char> png = encodePngRgb(width, height, rgb);
            EXPECT_EQ(png, encodePngRgb(width, height, rgb));
            EXPECT_EQ(pngColourType(png), grey ? 0 : 2);
            const fs::path path =
                tempDir() / ("edge_" + std::to_string(grey) + "_" + std::to_string(width) + "x" +
                             std::to_string(height) + ".png");
            writeBytes(path, png);
            expectSamePixels(readTextureRgba(path.string()), width, height, rgb);
        }
    }
}

TEST(ImageCodec, Srgb8MatchesTheTransferFunction) {
    EXPECT_EQ(toSrgb8(-1.0f), 0);
    EXPECT_EQ(toSrgb8(0.0f), 0);
    EXPECT_EQ(toSrgb8(0.0031308f), 10);  // 12.92 * 0.0031308 * 255 = 10.3
    EXPECT_EQ(toSrgb8(0.5f), 188);
    EXPECT_EQ(toSrgb8(1.0f), 255);
    EXPECT_EQ(toSrgb8(2.0f), 255);
}

TEST(ImageCodec, Base64) {
    EXPECT_EQ(base64({}), "");
    EXPECT_EQ(base64({'M'}), "TQ==");
    EXPECT_EQ(base64({'M', 'a'}), "TWE=");
    EXPECT_EQ(base64({'M', 'a', 'n'}), "TWFu");
}

// A PNG of `channels` 8-bit channels written through the module as is (the codec's own writer
// takes RGB only).
fs::path writeChannels(const std::string& name, int width, int height, int channels,
                       const std::vector<unsigned char>& pixels) {
    const fs::path path = tempDir() / name;
    char error[256] = "";
    EXPECT_EQ(imageModule().writePng8(path.c_str(), nullptr, nullptr, width, height, channels,
                                      pixels.data(), 6, 0, error, sizeof error),
              0)
        << error;
    return path;
}

TEST(TextureRgba, ExpandsOneToFourChannels) {
    // Two pixels per file; expected RGBA codes after the expansion documented in image_codec.h.
    struct Case {
        int channels;
        std::vector<unsigned char> pixels;
        std::vector<int> rgba;
    };
    const Case cases[] = {
        {1, {7, 250}, {7, 7, 7, 255, 250, 250, 250, 255}},
        {2, {7, 30, 250, 0}, {7, 7, 7, 30, 250, 250, 250, 0}},
        {3, {1, 2, 3, 200, 100, 50}, {1, 2, 3, 255, 200, 100, 50, 255}},
        // Alpha is not premultiplied into the colour: 200 stays 200 under alpha 10.
        {4, {200, 100, 50, 10, 9, 8, 7, 255}, {200, 100, 50, 10, 9, 8, 7, 255}},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.channels);
        const fs::path path =
            writeChannels("c" + std::to_string(c.channels) + ".png", 2, 1, c.channels, c.pixels);
        const TextureRgba t = readTextureRgba(path.string());
        EXPECT_EQ(t.fileChannels, c.channels);
        ASSERT_EQ(t.rgba.size(), 8u);
        for (size_t i = 0; i < 8; ++i) EXPECT_EQ(std::lround(t.rgba[i] * 255.0f), c.rgba[i]) << i;
    }
}

TEST(TextureRgba, ReadsJpeg) {
    // oiiotool --pattern constant:color=1,0.5,0.25 8x8 3 -d uint8 -o orange_8x8.jpg
    const TextureRgba t = readTextureRgba(SO_TEST_DATA_DIR "/images/orange_8x8.jpg");
    EXPECT_EQ(t.width, 8);
    EXPECT_EQ(t.height, 8);
    EXPECT_EQ(t.fileChannels, 3);
    for (size_t i = 0; i < t.rgba.size(); i += 4) {  // JPEG is lossy: a code or two either way
        EXPECT_NEAR(t.rgba[i], 1.0f, 2.5f / 255.0f);
        EXPECT_NEAR(t.rgba[i + 1], 0.5f, 2.5f / 255.0f);
        EXPECT_NEAR(t.rgba[i + 2], 0.25f, 2.5f / 255.0f);
        EXPECT_EQ(t.rgba[i + 3], 1.0f);
    }
}

// The message of the InputError that `f` throws, or "" when it throws none.
template <class F>
std::string inputError(F f) {
    try {
        f();
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        return e.what();
    }
    return "";
}

TEST(TextureRgba, BrokenForeignAndMissingFilesAreInputErrors) {
    const fs::path dir = tempDir();
    const fs::path full = dir / "full.png";
    writePngRgb(full.string(), 64, 64, randomRgb(64, 64, false, 4));
    std::vector<unsigned char> bytes = readBytes(full);
    bytes.resize(bytes.size() / 2);
    const fs::path truncated = dir / "truncated.png";
    writeBytes(truncated, bytes);
    const fs::path text = dir / "text.png";
    writeBytes(text, {'n', 'o', 't', ' ', 'a', 'n', ' ', 'i', 'm', 'a', 'g', 'e', '\n'});
    for (const fs::path& p : {truncated, text, dir / "missing.png"}) {
        const std::string e = inputError([&] { readTextureRgba(p.string()); });
        EXPECT_EQ(e.rfind(p.string() + ": cannot read the image: ", 0), 0u) << e;
    }
}

void appendChunk(std::vector<unsigned char>& png, const char* type,
                 const std::vector<unsigned char>& data) {
    for (int s = 24; s >= 0; s -= 8) png.push_back(uint8_t(data.size() >> s));
    const size_t start = png.size();
    png.insert(png.end(), type, type + 4);
    png.insert(png.end(), data.begin(), data.end());
    uint32_t crc = 0xffffffffu;  // over type and data, as PNG requires
    for (size_t i = start; i < png.size(); ++i) {
        crc ^= png[i];
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    crc ^= 0xffffffffu;
    for (int s = 24; s >= 0; s -= 8) png.push_back(uint8_t(crc >> s));
}

// A well-formed PNG header claiming width x height 8-bit RGB pixels, with an empty IDAT: what a
// hostile file would use to make a reader allocate.
std::vector<unsigned char> pngHeaderOnly(uint32_t width, uint32_t height) {
    std::vector<unsigned char> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    std::vector<unsigned char> ihdr;
    for (uint32_t v : {width, height})
        for (int s = 24; s >= 0; s -= 8) ihdr.push_back(uint8_t(v >> s));
    for (unsigned char c : {8, 2, 0, 0, 0}) ihdr.push_back(c);
    appendChunk(png, "IHDR", ihdr);
    appendChunk(png, "IDAT", {});
    appendChunk(png, "IEND", {});
    return png;
}

TEST(TextureRgba, OversizedImagesAreRefusedBeforeReadingPixels) {
    const fs::path dir = tempDir();
    const fs::path small = dir / "small.png";
    writePngRgb(small.string(), 300, 200, randomRgb(300, 200, false, 5));
    const std::string tooLarge = inputError([&] { readTextureRgba(small.string(), 256, 256); });
    EXPECT_NE(tooLarge.find("is 300 x 200 pixels, more than the limit of 256 x 256"),
              std::string::npos)
        << tooLarge;
    const std::string tooMany =
        inputError([&] { readTextureRgba(small.string(), 512, 512, 50000); });
    EXPECT_NE(tooMany.find("more than the limit of 50000 pixels"), std::string::npos) << tooMany;
    EXPECT_EQ(readTextureRgba(small.string(), 300, 200, 60000).width, 300);
    // 60000 x 60000 would be 54 GiB of floats: refused from the header alone.
    const fs::path huge = dir / "huge.png";
    writeBytes(huge, pngHeaderOnly(60000, 60000));
    const std::string e = inputError([&] { readTextureRgba(huge.string()); });
    EXPECT_EQ(e.rfind(huge.string() + ": ", 0), 0u) << e;
    EXPECT_NE(e.find("60000 x 60000"), std::string::npos) << e;
}

TEST(ImageModule, CandidatesAreTheEnvironmentVariableAloneOrBesideTheExecutable) {
    ASSERT_EQ(::setenv("SO_IMAGE_MODULE", "/somewhere/else.so", 1), 0);
    EXPECT_EQ(imageModuleCandidates(), std::vector<std::string>{"/somewhere/else.so"});
    ASSERT_EQ(::unsetenv("SO_IMAGE_MODULE"), 0);
    const std::vector<std::string> c = imageModuleCandidates();
    const fs::path exe = fs::read_symlink("/proc/self/exe");
    ASSERT_FALSE(c.empty());
    EXPECT_EQ(fs::path(c[0]).parent_path(), fs::weakly_canonical(exe.parent_path()));
}

bool mapsOpenImageIO() {
    std::ifstream maps("/proc/self/maps");
    std::stringstream s;
    s << maps.rdbuf();
    return s.str().find("libOpenImageIO") != std::string::npos;
}

// Death tests re-run this binary for the one test ("threadsafe" style), so the module is loaded,
// or not, there afresh whatever other tests did here.
TEST(ImageModuleDeathTest, WritingPngsLoadsNothingAndTheFirstReadLoadsOpenImageIO) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const std::string path = (tempDir() / "module_probe.png").string();
    EXPECT_EXIT(
        {
            const bool before = mapsOpenImageIO();
            base64({1, 2, 3});
            toSrgb8(0.5f);
            encodePngRgb(1, 1, {0.5f, 0.5f, 0.5f});
            writePngRgb(path, 2, 1, {0.5f, 0.5f, 0.5f, 1.0f, 0.0f, 0.0f});
            const bool afterWrites = mapsOpenImageIO() || loadedImageLibraryVersion() != "";
            readTextureRgba(path);
            std::cerr << "before " << before << " writes " << afterWrites << " read "
                      << mapsOpenImageIO() << " version " << !loadedImageLibraryVersion().empty()
                      << std::endl;
            std::_Exit(0);
        },
        ::testing::ExitedWithCode(0), "before 0 writes 0 read 1 version 1");
}

TEST(ImageModuleDeathTest, MissingModuleIsAOneLineErrorNamingThePath) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_EXIT(
        {
            ::setenv("SO_IMAGE_MODULE", "/nonexistent/so_image_oiio.so", 1);
            std::cerr << inputError([] { decodeTextureRgba({0x89, 'P', 'N', 'G'}); }) << std::endl;
            std::_Exit(0);
        },
        ::testing::ExitedWithCode(0),
        "^image module: cannot load OpenImageIO's image module.*"
        "/nonexistent/so_image_oiio.so: cannot open shared object file.*SO_IMAGE_MODULE");
}

}  // namespace
}  // namespace so
