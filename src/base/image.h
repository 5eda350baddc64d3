// An image in memory: what the renderer draws into and the image files are written from.
#pragma once

#include <vector>

namespace tracer {

// Linear RGB, unclamped, row 0 at the top of the view.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<double> rgb;  // width * height * 3, kept in double so 8-bit rounding is exact
};

}  // namespace tracer
