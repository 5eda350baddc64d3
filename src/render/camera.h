// The pinhole camera of conventions.md: w = normalize(eye - lookat), u = normalize(up x w),
// v = w x u; an image plane at distance `focal` whose height is 2 f tan(fovy / 2).
#pragma once

#include "frontend/scene.h"
#include "render/types.h"

namespace tracer {

class PinholeCamera {
public:
    PinholeCamera(const Camera& camera, int width, int height);

    // The primary ray through image position (x, y) in pixels: (0, 0) is the top-left corner
    // of the image, (width, height) the bottom-right; a pixel's centre is (i + 0.5, j + 0.5).
    Ray ray_through(Real x, Real y) const;

private:
    Vec3 eye_, u_, v_, w_;
    Real focal_, plane_width_, plane_height_;
    int width_, height_;
};

}  // namespace tracer
