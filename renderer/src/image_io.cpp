// Image files through OpenImageIO, written atomically.
#include <OpenImageIO/imageio.h>

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
    if (spec.width <= 0 || spec.height <= 0 || spec.width > 65536 || spec.height > 65536) {
        throw RenderError(path + ": unsupported image size " + std::to_string(spec.width) + "x" +
                          std::to_string(spec.height));
    }
    LoadedImage image;
    image.width = spec.width;
    image.height = spec.height;
    // Gray stays gray, gray+alpha becomes gray, RGB stays RGB, anything wider is RGBA.
    const int stored = spec.nchannels;
    image.channels = stored <= 2 ? 1 : stored == 3 ? 3 : 4;
    std::vector<std::uint8_t> all(std::size_t(spec.width) * spec.height * stored);
    if (!input->read_image(0, 0, 0, stored, OIIO::TypeDesc::UINT8, all.data())) {
        throw RenderError(path + ": " + input->geterror());
    }
    input->close();
    if (image.channels == stored) {
        image.pixels = std::move(all);
    } else {
        const std::size_t count = std::size_t(spec.width) * spec.height;
        image.pixels.resize(count * image.channels);
        for (std::size_t i = 0; i < count; ++i) {
            for (int c = 0; c < image.channels; ++c) image.pixels[i * image.channels + c] = all[i * stored + c];
        }
    }
    return image;
}

}  // namespace lodopt::renderer
