// An image in memory: what the renderer draws into and the image files are written from.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace tracer {

// Linear RGB, unclamped, row 0 at the top of the view. The image may be a window of a larger
// frame (a render region): its pixel (0, 0) is the frame's pixel (x0, y0).
struct Image {
    int width = 0;
    int height = 0;
    std::vector<double> rgb;  // width * height * 3, kept in double so 8-bit rounding is exact
    int x0 = 0, y0 = 0;       // where the window sits in the frame
    int frame_width = 0;      // the whole frame's size (the same as width and height when the
    int frame_height = 0;     // image is the whole frame)

    // True when the image is only part of its frame.
    bool is_window() const { return x0 != 0 || y0 != 0 || width != frame_width || height != frame_height; }
};

// round(255 v) of v clamped to [0, 1] (0 for NaN): the 8-bit value of conventions.md.
inline unsigned char to_8bit(double value) {
    if (!(value > 0)) return 0;
    return static_cast<unsigned char>(std::lround(255.0 * std::min(value, 1.0)));
}

// The sRGB curve (IEC 61966-2-1) of a linear value: 12.92 v up to 0.0031308, else
// 1.055 v^(1/2.4) - 0.055 (0 for v <= 0 and NaN, 1 for v >= 1).
inline double srgb_encoded(double value) {
    if (!(value > 0)) return 0;
    if (value >= 1) return 1;
    return value <= 0.0031308 ? 12.92 * value : 1.055 * std::pow(value, 1 / 2.4) - 0.055;
}

}  // namespace tracer
