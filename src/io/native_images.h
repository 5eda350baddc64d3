// The image formats tracer writes without OpenImageIO: PNG (through libpng) and binary PPM. They
// are what a render writes most, and loading OpenImageIO's 260 libraries costs a small frame's
// time ten times over (issue 57), so those two never load it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "base/image.h"
#include "io/eight_bit.h"

namespace tracer {

enum class NativeFormat { Png, Ppm };

// The native format `path`'s extension names (.png, .ppm, any case), or nullopt.
std::optional<NativeFormat> native_format(const std::string& path);

// The image encoded as `format` into `encoded`: 8-bit RGB, round(255 v) of v clamped to [0, 1],
// or of the sRGB-encoded v when `srgb` (a PNG then carries the sRGB chunk); an error message if
// the encoder failed.
std::optional<std::string> encode_native(NativeFormat format, const Image& image, bool srgb,
                                         std::vector<unsigned char>& encoded);

// True if the file at `path` is a whole image of `width` x `height` pixels: a PNG whose header
// says that size and that ends with its IEND chunk, a PPM of that size holding every byte; a file
// of another format only needs to be there and not empty (a resumed animation keeps such frames).
bool image_file_is_whole(const std::string& path, int width, int height);

}  // namespace tracer
