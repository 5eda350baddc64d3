// The pinhole camera of conventions.md: w = normalize(eye - lookat), u = normalize(up x w),
// v = w x u; an image plane at distance 1 (the scene's focal does not change the rays) whose height is 2 tan(fovy / 2).
#pragma once

#include "accel/types.h"
#include "scene/scene.h"

namespace tracer {

class PinholeCamera {
public:
    PinholeCamera(const Camera& camera, int width, int height);

    // The primary ray through image position (x, y) in pixels: (0, 0) is the top-left corner
    // of the image, (width, height) the bottom-right; a pixel's center is (i + 0.5, j + 0.5).
    Ray ray_through(Real x, Real y) const;
    const Vec3& eye() const { return eye_; }

    // The directions of ray_through(x_start + i, y) for i = 0 .. count - 1 (ray_through is this
    // with count 1), a row at a time so the square roots and divisions run several to a vector
    // instruction.
    void row_directions(Real x_start, Real y, int count, Vec3* out) const;

    // Where `point` appears in the image, in the pixel coordinates of ray_through; false if it
    // lies behind the eye.
    bool project(const Vec3& point, Real& x, Real& y) const;

private:
    Vec3 eye_, u_, v_, w_;
    Real focal_, plane_width_, plane_height_;
    // The unnormalised direction to image position (x, y) is corner_ + x step_x_ + y step_y_:
    // no division per ray.
    Vec3 corner_, step_x_, step_y_;
    int width_, height_;
};

}  // namespace tracer
