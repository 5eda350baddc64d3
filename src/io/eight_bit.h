// An image's 8-bit bytes, by the conventions' rounding (linear) or through the sRGB curve: what
// every 8-bit file and the browser's canvas get (native_images.h, web/playground.cpp).
#pragma once

#include "base/image.h"

namespace tracer {

// The image's 8-bit RGB bytes, row by row from the top, into `out` (image.rgb.size() bytes):
// round(255 v) of v clamped to [0, 1], or of the sRGB-encoded v when `srgb`.
void eight_bit_rows(const Image& image, bool srgb, unsigned char* out);

// True if the fast sRGB byte of `value` (a table of the curve's steps) is the curve's own,
// to_8bit(srgb_encoded(value)) (for the tests).
bool srgb_bytes_match_the_curve(double value);

}  // namespace tracer
