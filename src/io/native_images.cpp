#include "io/native_images.h"

#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <csetjmp>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace tracer {
namespace {

// The 8-bit RGB bytes of the image, row by row from the top.
std::vector<unsigned char> eight_bit_rows(const Image& image, bool srgb) {
    std::vector<unsigned char> bytes(image.rgb.size());
    eight_bit_rows(image, srgb, bytes.data());
    return bytes;
}

void append_bytes(png_structp png, png_bytep data, png_size_t length) {
    auto* out = static_cast<std::vector<unsigned char>*>(png_get_io_ptr(png));
    out->insert(out->end(), data, data + length);
}

void no_flush(png_structp) {}

// libpng's errors end in longjmp back to encode_png; its message is kept for the caller.
void on_png_error(png_structp png, png_const_charp message) {
    auto* error = static_cast<char*>(png_get_error_ptr(png));
    std::strncpy(error, message ? message : "libpng failed", 255);
    error[255] = '\0';
    png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}

// The PNG of `rows` (width x height RGB bytes) into `out`; false with `error` set on failure.
// No C++ object lives across setjmp here: the vectors belong to the caller.
bool encode_png(const unsigned char* rows, int width, int height, bool srgb, std::vector<unsigned char>* out,
                char* error) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, error, on_png_error, on_png_warning);
    if (!png) return false;
    png_infop info = png_create_info_struct(png);
    if (!info || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, info ? &info : nullptr);
        return false;
    }
    png_set_write_fn(png, out, append_bytes, no_flush);
    png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    // zlib's fastest level and one filter (Sub) for every row, not the default (level 6, filters
    // tried per row): an animation's frame 3.4 ms sooner at 320 x 240 for files about 15% larger
    // (docs/decisions.md, "PNG compression").
    png_set_compression_level(png, 1);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
    if (srgb) png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    for (int y = 0; y < height; ++y) png_write_row(png, rows + size_t(y) * size_t(width) * 3);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    return true;
}

}  // namespace

bool image_file_is_whole(const std::string& path, int width, int height) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) return false;
    const auto size = std::filesystem::file_size(path, error);
    if (error || size == 0) return false;
    const auto format = native_format(path);
    if (!format) return true;
    std::ifstream file(path, std::ios::binary);
    std::string bytes(std::min<uintmax_t>(size, 64), '\0');
    if (!file.read(bytes.data(), std::streamsize(bytes.size()))) return false;
    if (*format == NativeFormat::Ppm) {
        const std::string header = "P6\n" + std::to_string(width) + " " + std::to_string(height) + "\n255\n";
        return bytes.compare(0, header.size(), header) == 0 &&
               size == header.size() + size_t(width) * size_t(height) * 3;
    }
    // PNG: the signature, IHDR's width and height (big-endian, bytes 16..23), and IEND last.
    static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static constexpr unsigned char kEnd[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
    auto byte = [&](size_t i) { return static_cast<unsigned char>(bytes[i]); };
    auto big_endian = [&](size_t at) {
        return uint32_t(byte(at)) << 24 | uint32_t(byte(at + 1)) << 16 | uint32_t(byte(at + 2)) << 8 | byte(at + 3);
    };
    if (bytes.size() < 24 + sizeof kEnd || std::memcmp(bytes.data(), kSignature, 8) != 0 ||
        big_endian(16) != uint32_t(width) || big_endian(20) != uint32_t(height))
        return false;
    char end[sizeof kEnd];
    file.seekg(std::streamoff(size - sizeof kEnd));
    return file.read(end, sizeof end) && std::memcmp(end, kEnd, sizeof kEnd) == 0;
}

std::optional<NativeFormat> native_format(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (extension == ".png") return NativeFormat::Png;
    if (extension == ".ppm") return NativeFormat::Ppm;
    return std::nullopt;
}

std::optional<std::string> encode_native(NativeFormat format, const Image& image, bool srgb,
                                         std::vector<unsigned char>& encoded) {
    const std::vector<unsigned char> rows = eight_bit_rows(image, srgb);
    encoded.clear();
    if (format == NativeFormat::Ppm) {
        const std::string header =
            "P6\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n255\n";
        encoded.assign(header.begin(), header.end());
        encoded.insert(encoded.end(), rows.begin(), rows.end());
        return std::nullopt;
    }
    char error[256] = "libpng could not start";
    if (!encode_png(rows.data(), image.width, image.height, srgb, &encoded, error)) return std::string(error);
    return std::nullopt;
}

}  // namespace tracer
