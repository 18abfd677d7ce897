// Image files (renderer/src/image_io.cpp): every format lodopt writes reads back, the PNG
// variants other tools write (16-bit, palette with transparency, gray + alpha, interlaced) come
// in as 8-bit pixels, and hostile or foreign files are refused by name, without a crash.
#include <gtest/gtest.h>

#include <png.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "renderer/renderer.hpp"

using namespace lodopt;
namespace fs = std::filesystem;

namespace {

class ImageFilesTest : public ::testing::Test {
protected:
    void SetUp() override {
        mDir = fs::temp_directory_path() / ("lodopt-images-" + std::to_string(::getpid()));
        fs::create_directories(mDir);
    }
    void TearDown() override { fs::remove_all(mDir); }
    std::string path(const std::string& name) const { return (mDir / name).string(); }
    fs::path mDir;
};

// A smooth RGBA test frame (JPEG keeps smooth images close) with a depth ramp.
renderer::Frame testFrame(int width, int height) {
    renderer::Frame frame;
    frame.width = width;
    frame.height = height;
    frame.rgba.resize(std::size_t(width) * height * 4);
    frame.depth.resize(std::size_t(width) * height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            std::uint8_t* p = &frame.rgba[(std::size_t(y) * width + x) * 4];
            p[0] = std::uint8_t(x * 255 / (width - 1));
            p[1] = std::uint8_t(y * 255 / (height - 1));
            p[2] = std::uint8_t(128);
            p[3] = std::uint8_t(200 + (x + y) % 50);
            frame.depth[std::size_t(y) * width + x] = float(x + y) / float(width + height);
        }
    }
    return frame;
}

// Writes a PNG with libpng as another tool would: `rows` holds raw rows of the given type.
void writePng(const std::string& path, int width, int height, int bitDepth, int colorType,
              const std::vector<std::vector<std::uint8_t>>& rows, bool interlaced = false,
              const std::vector<png_color>& palette = {}, const std::vector<png_byte>& alphas = {}) {
    std::FILE* file = std::fopen(path.c_str(), "wb");
    ASSERT_NE(file, nullptr);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    png_init_io(png, file);
    png_set_IHDR(png, info, width, height, bitDepth, colorType, interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (!palette.empty()) png_set_PLTE(png, info, palette.data(), int(palette.size()));
    if (!alphas.empty()) png_set_tRNS(png, info, alphas.data(), int(alphas.size()), nullptr);
    png_write_info(png, info);
    std::vector<png_bytep> pointers;
    for (const auto& row : rows) pointers.push_back(const_cast<png_bytep>(row.data()));
    png_write_image(png, pointers.data());
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    std::fclose(file);
}

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

TEST_F(ImageFilesTest, EveryFormatLodoptWritesReadsBack) {
    const renderer::Frame frame = testFrame(37, 23);
    renderer::writeColorImage(path("a.png"), frame);
    renderer::LoadedImage png = renderer::readImage(path("a.png"));
    EXPECT_EQ(png.width, 37);
    EXPECT_EQ(png.height, 23);
    ASSERT_EQ(png.channels, 4);
    EXPECT_EQ(png.pixels, frame.rgba);

    // PPM: RGB exactly (no alpha in the format).
    renderer::writeColorImage(path("a.ppm"), frame);
    const renderer::LoadedImage ppm = renderer::readImage(path("a.ppm"));
    ASSERT_EQ(ppm.channels, 3);
    ASSERT_EQ(ppm.pixels.size(), std::size_t(37 * 23 * 3));
    for (std::size_t i = 0; i < std::size_t(37 * 23); ++i) {
        for (int c = 0; c < 3; ++c) ASSERT_EQ(ppm.pixels[i * 3 + c], frame.rgba[i * 4 + c]) << i;
    }

    // JPEG: RGB, lossy but close on a smooth image; the extension's case does not matter.
    renderer::writeColorImage(path("a.JPG"), frame);
    const renderer::LoadedImage jpeg = renderer::readImage(path("a.JPG"));
    EXPECT_EQ(jpeg.width, 37);
    EXPECT_EQ(jpeg.height, 23);
    ASSERT_EQ(jpeg.channels, 3);
    int worst = 0;
    for (std::size_t i = 0; i < std::size_t(37 * 23); ++i) {
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(jpeg.pixels[i * 3 + c]) - int(frame.rgba[i * 4 + c])));
    }
    EXPECT_LE(worst, 12);

    // Depth: OpenEXR (its magic number) and PFM (header, then rows bottom to top).
    renderer::writeDepthImage(path("d.exr"), frame);
    EXPECT_EQ(slurp(path("d.exr")).substr(0, 4), std::string("\x76\x2f\x31\x01", 4));
    renderer::writeDepthImage(path("d.pfm"), frame);
    const std::string pfm = slurp(path("d.pfm"));
    const std::string header = "Pf\n37 23\n-1.0\n";
    ASSERT_EQ(pfm.size(), header.size() + 37 * 23 * sizeof(float));
    EXPECT_EQ(pfm.substr(0, header.size()), header);
    float firstOfBottomRow = 0.0f;
    std::memcpy(&firstOfBottomRow, pfm.data() + header.size(), sizeof(float));
    EXPECT_EQ(firstOfBottomRow, frame.depth[std::size_t(22) * 37]);

    // Only the finished files: no temporary left behind.
    EXPECT_EQ(std::distance(fs::directory_iterator(mDir), fs::directory_iterator{}), 5);
}

TEST_F(ImageFilesTest, OtherToolsPngVariantsArriveAsEightBitPixels) {
    // 16-bit gray + alpha: gray kept, alpha dropped, 16 bits scaled with rounding.
    std::vector<std::vector<std::uint8_t>> rows16 = {{0x12, 0x34, 0xFF, 0xFF, 0xFF, 0xFF, 0x00, 0x00},
                                                     {0x80, 0x80, 0x00, 0x10, 0x00, 0x00, 0x12, 0x34}};
    writePng(path("ga16.png"), 2, 2, 16, PNG_COLOR_TYPE_GRAY_ALPHA, rows16);
    const renderer::LoadedImage ga = renderer::readImage(path("ga16.png"));
    ASSERT_EQ(ga.channels, 1);
    auto scaled = [](unsigned v) { return std::uint8_t((v * 255 + 32767) / 65535); };
    EXPECT_EQ(ga.pixels, (std::vector<std::uint8_t>{scaled(0x1234), 255, scaled(0x8080), 0}));

    // Palette with a transparent entry: RGBA.
    const std::vector<png_color> palette = {{10, 20, 30}, {200, 100, 50}};
    writePng(path("palette.png"), 3, 1, 8, PNG_COLOR_TYPE_PALETTE, {{0, 1, 0}}, false, palette, {0});
    const renderer::LoadedImage indexed = renderer::readImage(path("palette.png"));
    ASSERT_EQ(indexed.channels, 4);
    EXPECT_EQ(indexed.pixels, (std::vector<std::uint8_t>{10, 20, 30, 0, 200, 100, 50, 255, 10, 20, 30, 0}));

    // 1-bit gray, interlaced (Adam7): the same pixels as stored, expanded to 0 / 255.
    std::vector<std::vector<std::uint8_t>> bits;
    std::vector<std::uint8_t> expected;
    for (int y = 0; y < 9; ++y) {
        std::vector<std::uint8_t> row(2, 0);
        for (int x = 0; x < 11; ++x) {
            const bool on = (x * 3 + y * 5) % 7 < 3;
            if (on) row[std::size_t(x / 8)] |= std::uint8_t(0x80 >> (x % 8));
            expected.push_back(on ? 255 : 0);
        }
        bits.push_back(row);
    }
    writePng(path("bits.png"), 11, 9, 1, PNG_COLOR_TYPE_GRAY, bits, true);
    const renderer::LoadedImage bilevel = renderer::readImage(path("bits.png"));
    ASSERT_EQ(bilevel.channels, 1);
    EXPECT_EQ(bilevel.pixels, expected);

    // RGB stays RGB; the name's extension does not decide the format, the bytes do.
    writePng(path("rgb.data"), 1, 1, 8, PNG_COLOR_TYPE_RGB, {{1, 2, 3}});
    const renderer::LoadedImage rgb = renderer::readImage(path("rgb.data"));
    ASSERT_EQ(rgb.channels, 3);
    EXPECT_EQ(rgb.pixels, (std::vector<std::uint8_t>{1, 2, 3}));
}

TEST_F(ImageFilesTest, PnmHeadersCommentsAndSixteenBitSamples) {
    std::ofstream(path("c.pgm"), std::ios::binary) << "P5\n# made by hand\n3 1 # width height\n65535\n"
                                                   << std::string("\x00\x00\x80\x00\xff\xff", 6);
    const renderer::LoadedImage gray = renderer::readImage(path("c.pgm"));
    ASSERT_EQ(gray.channels, 1);
    EXPECT_EQ(gray.pixels, (std::vector<std::uint8_t>{0, 128, 255}));
    std::ofstream(path("m.ppm"), std::ios::binary) << "P6 1 1 15 " << std::string("\x0f\x00\x07", 3);
    const renderer::LoadedImage small = renderer::readImage(path("m.ppm"));
    ASSERT_EQ(small.channels, 3);
    EXPECT_EQ(small.pixels, (std::vector<std::uint8_t>{255, 0, 119}));
}

TEST_F(ImageFilesTest, ForeignTruncatedOrHostileFilesAreRefusedByName) {
    const renderer::Frame frame = testFrame(16, 16);
    renderer::writeColorImage(path("whole.png"), frame);
    renderer::writeColorImage(path("whole.jpg"), frame);
    const std::string png = slurp(path("whole.png")), jpeg = slurp(path("whole.jpg"));
    std::ofstream(path("cut.png"), std::ios::binary) << png.substr(0, png.size() / 2);
    std::ofstream(path("cut.jpg"), std::ios::binary) << jpeg.substr(0, jpeg.size() / 2);
    // The image data ends early at a marker (here the end-of-image one): libjpeg would fill the
    // rest with gray, as it would the rest of a 16384 x 16384 image a few bytes long.
    // (128 x 128, so that half the file lies in the image data, past the tables.)
    renderer::writeColorImage(path("large.jpg"), testFrame(128, 128));
    const std::string large = slurp(path("large.jpg"));
    std::ofstream(path("early.jpg"), std::ios::binary) << large.substr(0, large.size() / 2) << "\xFF\xD9";
    std::ofstream(path("image.tga"), std::ios::binary) << std::string("\0\0\2\0\0\0\0\0\0\0\0\0\1\0\1\0\x18\0\1\2\3", 21);
    std::ofstream(path("short.ppm"), std::ios::binary) << "P6\n4000 4000\n255\n" << std::string(10, 'x');
    std::ofstream(path("maximum.pgm"), std::ios::binary) << "P5 1 1 70000 " << std::string(2, 'x');
    // A JPEG header promising 60000 x 60000 pixels (SOF0), then nothing.
    const unsigned char huge[] = {0xFF, 0xD8, 0xFF, 0xC0, 0x00, 0x0B, 0x08, 0xEA, 0x60, 0xEA, 0x60, 0x01,
                                  0x01, 0x11, 0x00, 0xFF, 0xD9};
    std::ofstream(path("huge.jpg"), std::ios::binary).write(reinterpret_cast<const char*>(huge), sizeof huge);
    fs::create_directories(mDir / "folder.png");
    for (const char* name : {"cut.png", "cut.jpg", "early.jpg", "image.tga", "short.ppm", "maximum.pgm", "huge.jpg", "folder.png",
                             "missing.png"}) {
        try {
            renderer::readImage(path(name));
            ADD_FAILURE() << name << " was read";
        } catch (const renderer::RenderError& error) {
            EXPECT_NE(std::string(error.what()).find(name), std::string::npos) << error.what();
        }
    }
    // Writing: an unknown type is refused before anything is written.
    EXPECT_THROW(renderer::writeColorImage(path("frame.tif"), frame), renderer::RenderError);
    EXPECT_THROW(renderer::writeDepthImage(path("depth.png"), frame), renderer::RenderError);
    EXPECT_FALSE(fs::exists(path("frame.tif")));
    EXPECT_FALSE(fs::exists(path("depth.png")));
}
