// Image files through OpenImageIO, written atomically.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <memory>

#include "renderer/renderer.hpp"
#include "scenes/atomic_file.hpp"

namespace lodopt::renderer {
namespace {

void writeImage(const std::string& path, int width, int height, int channels, OIIO::TypeDesc type,
                const void* pixels) {
    scenes::writeFileAtomically(path, [&](const std::string& temporary) {
        auto output = OIIO::ImageOutput::create(temporary);
        if (!output) throw RenderError(path + ": cannot write this image format (" + OIIO::geterror() + ")");
        OIIO::ImageSpec spec(width, height, channels, type);
        if (channels == 1 && type == OIIO::TypeDesc::FLOAT) spec.channelnames = {"Z"};
        // Level 1 PNG compression: 2x faster than the default for a few percent more bytes.
        spec.attribute("png:compressionLevel", 1);
        if (!output->open(temporary, spec) || !output->write_image(type, pixels) || !output->close()) {
            throw RenderError(path + ": " + output->geterror());
        }
    });
}

}  // namespace

void writeColorImage(const std::string& path, const Frame& frame) {
    writeImage(path, frame.width, frame.height, 4, OIIO::TypeDesc::UINT8, frame.rgba.data());
}

void writeDepthImage(const std::string& path, const Frame& frame) {
    writeImage(path, frame.width, frame.height, 1, OIIO::TypeDesc::FLOAT, frame.depth.data());
}

LoadedImage readImage(const std::string& path) {
    auto input = OIIO::ImageInput::open(path);
    if (!input) throw RenderError(path + ": cannot read image (" + OIIO::geterror() + ")");
    const OIIO::ImageSpec& spec = input->spec();
    // 16384 is the largest --size lodopt renders. A header may promise any size: the bound and
    // the uninitialised buffer below keep a tiny hostile file from claiming gigabytes.
    if (spec.width <= 0 || spec.height <= 0 || spec.width > 16384 || spec.height > 16384 || spec.nchannels <= 0) {
        throw RenderError(path + ": unsupported image size " + std::to_string(spec.width) + "x" +
                          std::to_string(spec.height) + " (1..16384 pixels each)");
    }
    LoadedImage image;
    image.width = spec.width;
    image.height = spec.height;
    // Gray stays gray, gray+alpha becomes gray, RGB stays RGB, anything wider is RGBA (only the
    // first four channels are read).
    const int stored = std::min(spec.nchannels, 4);
    image.channels = stored <= 2 ? 1 : stored == 3 ? 3 : 4;
    const std::size_t count = std::size_t(spec.width) * spec.height;
    // Not value-initialised: pages are touched only as the decoder fills them.
    std::unique_ptr<std::uint8_t[]> all(new std::uint8_t[count * stored]);
    if (!input->read_image(0, 0, 0, stored, OIIO::TypeDesc::UINT8, all.get())) {
        throw RenderError(path + ": " + input->geterror());
    }
    input->close();
    image.pixels.resize(count * image.channels);
    for (std::size_t i = 0; i < count; ++i) {
        for (int c = 0; c < image.channels; ++c) image.pixels[i * image.channels + c] = all[i * stored + c];
    }
    return image;
}

}  // namespace lodopt::renderer
