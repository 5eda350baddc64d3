// Image files through OpenImageIO, format chosen by the file extension. 8-bit formats get
// round(255 v) of v clamped to [0, 1], no gamma (or of the sRGB-encoded v, Encoding::Srgb);
// float formats (EXR, HDR, PFM) get the unclamped linear values. Files are written to a temporary name and renamed, so
// a failed or interrupted write never leaves a truncated image behind.
#pragma once

#include <optional>
#include <string>

#include "base/image.h"
#include "scene/scene.h"

namespace tracer {

// An error message if `path` cannot be written as an image (unknown extension, no such
// folder), checked before rendering so no time is wasted.
std::optional<std::string> check_output_path(const std::string& path);

// Writes the image (a window where the format can record it: EXR's data window inside the
// frame's display window), 8-bit formats by `encoding`; returns an error message on failure
// (and leaves `path` untouched).
std::optional<std::string> write_image(const std::string& path, const Image& image,
                                       Encoding encoding = Encoding::Linear);

// The most bytes of texels one image pattern's file may hold (8-bit RGB: 16384 x 16384 texels).
constexpr size_t kMostTexelBytes = size_t(3) << 28;

// Reads the texels of every image the scene's patterns name (ImageFile::texels); false if one
// cannot be read (reported at its `file` value).
bool load_images(SceneDescription& scene, Diagnostics& diagnostics);

}  // namespace tracer
