// An image in memory: what the renderer draws into and the image files are written from.
#pragma once

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

}  // namespace tracer
