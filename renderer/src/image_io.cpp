// Image files: PNG (libpng), JPEG (libjpeg), binary PNM, and for depth OpenEXR and PFM; written
// atomically. Small libraries on purpose: OpenImageIO, which did this before, loads about 260
// shared libraries, and binding their symbols cost every lodopt process 0.3 s at start
// (docs/renderer.md "Image files").
//
// libpng and libjpeg report errors by longjmp. Each decoder's setjmp sits in a function whose
// own locals are not changed after it; everything that changes lives in a caller's object,
// and no C++ object is skipped by the jump (only the libraries' C frames are).
#include <png.h>
#include <jpeglib.h>
#include <jerror.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "renderer/renderer.hpp"
#include "scenes/atomic_file.hpp"

namespace lodopt::renderer {
namespace {

// The largest side lodopt renders (--size); a header may promise any size.
constexpr int kMaxSide = 16384;

struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

File openFile(const std::string& path, const char* mode) {
    File file(std::fopen(path.c_str(), mode));
    if (!file) throw RenderError(path + ": cannot open (" + std::strerror(errno) + ")");
    return file;
}

std::string lowerExtension(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
    return extension;
}

void checkSize(const std::string& path, long long width, long long height) {
    if (width <= 0 || height <= 0 || width > kMaxSide || height > kMaxSide) {
        throw RenderError(path + ": unsupported image size " + std::to_string(width) + "x" + std::to_string(height) +
                          " (1.." + std::to_string(kMaxSide) + " pixels each)");
    }
}

// A decoder's output buffer, not value-initialised: a header may promise 16384 x 16384 pixels
// in a file of a few bytes, and pages are only touched as the decoder fills them.
using Buffer = std::unique_ptr<std::uint8_t[]>;

// The image of `count` pixels of `stored` channels in `buffer`, keeping the first channels:
// gray stays gray, gray+alpha becomes gray, RGB stays RGB, RGBA stays RGBA.
LoadedImage loaded(int width, int height, const std::uint8_t* buffer, int stored) {
    LoadedImage image;
    image.width = width;
    image.height = height;
    image.channels = stored <= 2 ? 1 : stored == 3 ? 3 : 4;
    const std::size_t count = std::size_t(width) * height;
    image.pixels.resize(count * image.channels);
    if (stored == image.channels) {
        std::memcpy(image.pixels.data(), buffer, image.pixels.size());
        return image;
    }
    for (std::size_t i = 0; i < count; ++i) {
        for (int c = 0; c < image.channels; ++c) image.pixels[i * image.channels + c] = buffer[i * stored + c];
    }
    return image;
}

// ---- PNG ----------------------------------------------------------------------------------

struct PngJob {
    std::string message;  // libpng's error, when it longjmps
    Buffer pixels;
    std::vector<png_bytep> rows;
    png_uint_32 width = 0, height = 0;
    int channels = 0;
    bool tooLarge = false;
};

[[noreturn]] void pngError(png_structp png, png_const_charp message) {
    static_cast<PngJob*>(png_get_error_ptr(png))->message = message ? message : "libpng error";
    png_longjmp(png, 1);
}
void pngWarning(png_structp, png_const_charp) {}

bool decodePng(png_structp png, png_infop info, std::FILE* file, PngJob& job) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_init_io(png, file);
    png_read_info(png, info);
    job.width = png_get_image_width(png, info);
    job.height = png_get_image_height(png, info);
    if (job.width == 0 || job.height == 0 || job.width > png_uint_32(kMaxSide) || job.height > png_uint_32(kMaxSide)) {
        job.tooLarge = true;
        return true;
    }
    // Everything to 8 bits per channel: palettes and low bit depths expanded, 16 bits scaled
    // (rounded), transparency as an alpha channel.
    png_set_expand(png);
    png_set_scale_16(png);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    job.channels = png_get_channels(png, info);
    const std::size_t stride = png_get_rowbytes(png, info);
    job.pixels.reset(new std::uint8_t[stride * job.height]);
    job.rows.resize(job.height);
    for (png_uint_32 y = 0; y < job.height; ++y) job.rows[y] = job.pixels.get() + stride * y;
    png_read_image(png, job.rows.data());
    png_read_end(png, nullptr);
    return true;
}

LoadedImage readPng(const std::string& path, std::FILE* file) {
    PngJob job;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &job, pngError, pngWarning);
    if (!png) throw RenderError(path + ": out of memory");
    png_infop info = png_create_info_struct(png);
    const bool ok = info && decodePng(png, info, file, job);
    png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
    if (!ok) throw RenderError(path + ": " + (job.message.empty() ? "cannot decode PNG" : job.message));
    if (job.tooLarge) checkSize(path, job.width, job.height);
    return loaded(int(job.width), int(job.height), job.pixels.get(), job.channels);
}

bool encodePng(png_structp png, png_infop info, std::FILE* file, const Frame& frame) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_init_io(png, file);
    // Level 1: about twice as fast as the default for a few percent more bytes.
    png_set_compression_level(png, 1);
    png_set_IHDR(png, info, png_uint_32(frame.width), png_uint_32(frame.height), 8, PNG_COLOR_TYPE_RGBA,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < frame.height; ++y) {
        png_write_row(png, frame.rgba.data() + std::size_t(y) * frame.width * 4);
    }
    png_write_end(png, nullptr);
    return true;
}

void writePng(const std::string& path, std::FILE* file, const Frame& frame) {
    PngJob job;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &job, pngError, pngWarning);
    if (!png) throw RenderError(path + ": out of memory");
    png_infop info = png_create_info_struct(png);
    const bool ok = info && encodePng(png, info, file, frame);
    png_destroy_write_struct(&png, info ? &info : nullptr);
    if (!ok) throw RenderError(path + ": " + (job.message.empty() ? "cannot write PNG" : job.message));
}

// ---- JPEG ---------------------------------------------------------------------------------

struct JpegError {
    jpeg_error_mgr manager;  // first: libjpeg sees a jpeg_error_mgr*
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX] = {};
};

[[noreturn]] void jpegErrorExit(j_common_ptr info) {
    auto* error = reinterpret_cast<JpegError*>(info->err);
    info->err->format_message(info, error->message);
    std::longjmp(error->jump, 1);
}
// Warnings are silent, except image data that ends early, at the end of the file or at a
// marker inside it: libjpeg would fill the rest of a claimed 16384 x 16384 image with gray (a
// 358-byte file promising 1808 x 12544 pixels took the fuzzer 30 s to score).
void jpegMessage(j_common_ptr info, int level) {
    const int code = info->err->msg_code;
    if (level < 0 && (code == JWRN_JPEG_EOF || code == JWRN_HIT_MARKER)) jpegErrorExit(info);
}
// libjpeg's own memory for one image (progressive images keep every coefficient): at most this.
constexpr long kJpegMemoryBytes = 1l << 30;

struct JpegJob {
    Buffer pixels;
    JDIMENSION width = 0, height = 0;
    int channels = 0;
    bool tooLarge = false, unsupported = false;
};

bool decodeJpeg(jpeg_decompress_struct& info, JpegError& error, std::FILE* file, JpegJob& job) {
    if (setjmp(error.jump)) return false;
    jpeg_create_decompress(&info);
    info.mem->max_memory_to_use = kJpegMemoryBytes;
    jpeg_stdio_src(&info, file);
    jpeg_read_header(&info, TRUE);
    job.width = info.image_width;
    job.height = info.image_height;
    if (job.width == 0 || job.height == 0 || job.width > JDIMENSION(kMaxSide) || job.height > JDIMENSION(kMaxSide)) {
        job.tooLarge = true;
        return true;
    }
    if (info.jpeg_color_space == JCS_CMYK || info.jpeg_color_space == JCS_YCCK) {
        job.unsupported = true;
        return true;
    }
    info.out_color_space = info.jpeg_color_space == JCS_GRAYSCALE ? JCS_GRAYSCALE : JCS_RGB;
    jpeg_start_decompress(&info);
    job.channels = info.output_components;
    const std::size_t stride = std::size_t(info.output_width) * job.channels;
    job.pixels.reset(new std::uint8_t[stride * info.output_height]);
    while (info.output_scanline < info.output_height) {
        JSAMPROW row = job.pixels.get() + stride * info.output_scanline;
        jpeg_read_scanlines(&info, &row, 1);
    }
    jpeg_finish_decompress(&info);
    return true;
}

LoadedImage readJpeg(const std::string& path, std::FILE* file) {
    jpeg_decompress_struct info{};
    JpegError error;
    info.err = jpeg_std_error(&error.manager);
    error.manager.error_exit = jpegErrorExit;
    error.manager.emit_message = jpegMessage;
    JpegJob job;
    const bool ok = decodeJpeg(info, error, file, job);
    jpeg_destroy_decompress(&info);
    if (!ok) throw RenderError(path + ": " + error.message);
    if (job.tooLarge) checkSize(path, job.width, job.height);
    if (job.unsupported) throw RenderError(path + ": CMYK JPEG images are not supported (gray or RGB)");
    return loaded(int(job.width), int(job.height), job.pixels.get(), job.channels);
}

bool encodeJpeg(jpeg_compress_struct& info, JpegError& error, std::FILE* file, const Frame& frame,
                std::vector<std::uint8_t>& row) {
    if (setjmp(error.jump)) return false;
    jpeg_create_compress(&info);
    jpeg_stdio_dest(&info, file);
    info.image_width = JDIMENSION(frame.width);
    info.image_height = JDIMENSION(frame.height);
    info.input_components = 3;
    info.in_color_space = JCS_RGB;
    jpeg_set_defaults(&info);
    jpeg_set_quality(&info, 95, TRUE);
    jpeg_start_compress(&info, TRUE);
    while (info.next_scanline < info.image_height) {
        const std::uint8_t* rgba = frame.rgba.data() + std::size_t(info.next_scanline) * frame.width * 4;
        for (int x = 0; x < frame.width; ++x) std::memcpy(&row[std::size_t(x) * 3], rgba + std::size_t(x) * 4, 3);
        JSAMPROW pointer = row.data();
        jpeg_write_scanlines(&info, &pointer, 1);
    }
    jpeg_finish_compress(&info);
    return true;
}

void writeJpeg(const std::string& path, std::FILE* file, const Frame& frame) {
    jpeg_compress_struct info{};
    JpegError error;
    info.err = jpeg_std_error(&error.manager);
    error.manager.error_exit = jpegErrorExit;
    error.manager.emit_message = jpegMessage;
    std::vector<std::uint8_t> row(std::size_t(frame.width) * 3);  // RGB: JPEG has no alpha
    const bool ok = encodeJpeg(info, error, file, frame, row);
    jpeg_destroy_compress(&info);
    if (!ok) throw RenderError(path + ": " + error.message);
}

// ---- PNM (binary P5 gray, P6 RGB) and PFM ---------------------------------------------------

// A header number after whitespace and '#' comments; -1 when there is none.
long long pnmNumber(std::FILE* file) {
    int c = std::fgetc(file);
    for (;;) {
        while (c != EOF && std::isspace(c)) c = std::fgetc(file);
        if (c != '#') break;
        while (c != EOF && c != '\n') c = std::fgetc(file);
    }
    if (c == EOF || !std::isdigit(c)) return -1;
    long long value = 0;
    for (; c != EOF && std::isdigit(c); c = std::fgetc(file)) {
        value = value * 10 + (c - '0');
        if (value > (1ll << 40)) return -1;
    }
    return value;  // the one whitespace character after the number is consumed
}

LoadedImage readPnm(const std::string& path, std::FILE* file, int kind) {
    const long long width = pnmNumber(file), height = pnmNumber(file), maximum = pnmNumber(file);
    if (width < 0 || height < 0 || maximum < 1 || maximum > 65535) {
        throw RenderError(path + ": bad PNM header (width, height, maximum value 1..65535)");
    }
    checkSize(path, width, height);
    LoadedImage image;
    image.width = int(width);
    image.height = int(height);
    image.channels = kind == '5' ? 1 : 3;
    const std::size_t samples = std::size_t(width) * height * image.channels;
    const std::size_t bytesPerSample = maximum > 255 ? 2 : 1;
    const long start = std::ftell(file);
    std::fseek(file, 0, SEEK_END);
    const long end = std::ftell(file);
    std::fseek(file, start, SEEK_SET);
    if (start < 0 || end < start || std::size_t(end - start) < samples * bytesPerSample) {
        throw RenderError(path + ": truncated PNM pixels");
    }
    std::vector<std::uint8_t> raw(samples * bytesPerSample);
    if (std::fread(raw.data(), 1, raw.size(), file) != raw.size()) throw RenderError(path + ": truncated PNM pixels");
    image.pixels.resize(samples);
    for (std::size_t i = 0; i < samples; ++i) {
        const unsigned value = bytesPerSample == 2 ? unsigned(raw[2 * i]) << 8 | raw[2 * i + 1] : raw[i];
        image.pixels[i] = std::uint8_t((std::min<unsigned>(value, unsigned(maximum)) * 255u + unsigned(maximum) / 2) /
                                       unsigned(maximum));
    }
    return image;
}

void writePpm(const std::string& path, std::FILE* file, const Frame& frame) {
    std::fprintf(file, "P6\n%d %d\n255\n", frame.width, frame.height);
    std::vector<std::uint8_t> row(std::size_t(frame.width) * 3);
    for (int y = 0; y < frame.height; ++y) {
        const std::uint8_t* rgba = frame.rgba.data() + std::size_t(y) * frame.width * 4;
        for (int x = 0; x < frame.width; ++x) std::memcpy(&row[std::size_t(x) * 3], rgba + std::size_t(x) * 4, 3);
        if (std::fwrite(row.data(), 1, row.size(), file) != row.size()) throw RenderError(path + ": write failed");
    }
}

// PFM: one float channel, little-endian (negative scale), rows bottom to top.
void writePfm(const std::string& path, std::FILE* file, const Frame& frame) {
    static_assert(std::endian::native == std::endian::little);
    std::fprintf(file, "Pf\n%d %d\n-1.0\n", frame.width, frame.height);
    for (int y = frame.height - 1; y >= 0; --y) {
        const float* row = frame.depth.data() + std::size_t(y) * frame.width;
        if (std::fwrite(row, sizeof(float), std::size_t(frame.width), file) != std::size_t(frame.width)) {
            throw RenderError(path + ": write failed");
        }
    }
}

void writeExrDepth(const std::string& path, const std::string& temporary, const Frame& frame) {
    try {
        Imf::Header header(frame.width, frame.height);
        header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
        Imf::OutputFile output(temporary.c_str(), header);
        Imf::FrameBuffer buffer;
        buffer.insert("Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(frame.depth.data())),
                                      sizeof(float), sizeof(float) * std::size_t(frame.width)));
        output.setFrameBuffer(buffer);
        output.writePixels(frame.height);
    } catch (const std::exception& error) {
        throw RenderError(path + ": " + error.what());
    }
}

void checkFrame(const std::string& path, const Frame& frame, bool depth) {
    const std::size_t pixels = std::size_t(std::max(frame.width, 0)) * std::max(frame.height, 0);
    if (frame.width <= 0 || frame.height <= 0 || (depth ? frame.depth.size() : frame.rgba.size() / 4) != pixels) {
        throw RenderError(path + ": nothing to write (empty or inconsistent frame)");
    }
}

// Closes a written file: buffered writes fail here (a full disk), not in fwrite.
void closeWritten(const std::string& path, File file) {
    const bool failed = std::ferror(file.get()) != 0;
    if (std::fclose(file.release()) != 0 || failed) throw RenderError(path + ": write failed");
}

}  // namespace

std::string colorImageTypeError(const std::string& path) {
    const std::string extension = lowerExtension(path);
    if (extension.empty() || extension == ".png" || extension == ".jpg" || extension == ".jpeg" || extension == ".ppm") {
        return {};
    }
    return path + ": cannot write images of type '" + extension + "' (png, jpg, ppm)";
}

std::string depthImageTypeError(const std::string& path) {
    const std::string extension = lowerExtension(path);
    if (extension == ".exr" || extension == ".pfm") return {};
    return path + ": cannot write depth images of type '" + extension + "' (exr, pfm)";
}

void writeColorImage(const std::string& path, const Frame& frame) {
    if (const std::string error = colorImageTypeError(path); !error.empty()) throw RenderError(error);
    checkFrame(path, frame, false);
    const std::string extension = lowerExtension(path);
    enum class Format { Png, Jpeg, Ppm };
    const Format format = extension == ".jpg" || extension == ".jpeg" ? Format::Jpeg
                          : extension == ".ppm"                       ? Format::Ppm
                                                                      : Format::Png;
    scenes::writeFileAtomically(path, [&](const std::string& temporary) {
        File file = openFile(temporary, "wb");
        switch (format) {
            case Format::Png: writePng(path, file.get(), frame); break;
            case Format::Jpeg: writeJpeg(path, file.get(), frame); break;
            case Format::Ppm: writePpm(path, file.get(), frame); break;
        }
        closeWritten(path, std::move(file));
    });
}

void writeDepthImage(const std::string& path, const Frame& frame) {
    if (const std::string error = depthImageTypeError(path); !error.empty()) throw RenderError(error);
    checkFrame(path, frame, true);
    const std::string extension = lowerExtension(path);
    scenes::writeFileAtomically(path, [&](const std::string& temporary) {
        if (extension == ".exr") {
            writeExrDepth(path, temporary, frame);
            return;
        }
        File file = openFile(temporary, "wb");
        writePfm(path, file.get(), frame);
        closeWritten(path, std::move(file));
    });
}

LoadedImage readImage(const std::string& path) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) {
        throw RenderError(path + ": cannot read image (" +
                          (std::filesystem::exists(path, error) ? "not a regular file" : "no such file") + ")");
    }
    File file = openFile(path, "rb");
    // The format from the first bytes, whatever the file's name says.
    std::uint8_t magic[8] = {};
    const std::size_t got = std::fread(magic, 1, sizeof(magic), file.get());
    std::rewind(file.get());
    if (got >= 8 && png_sig_cmp(magic, 0, 8) == 0) return readPng(path, file.get());
    if (got >= 3 && magic[0] == 0xFF && magic[1] == 0xD8 && magic[2] == 0xFF) return readJpeg(path, file.get());
    if (got >= 3 && magic[0] == 'P' && (magic[1] == '5' || magic[1] == '6') && std::isspace(magic[2])) {
        std::fseek(file.get(), 2, SEEK_SET);
        return readPnm(path, file.get(), magic[1]);
    }
    throw RenderError(path + ": cannot read image (not a PNG, JPEG or binary PNM file)");
}

}  // namespace lodopt::renderer
