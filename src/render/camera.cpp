#include "render/camera.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace tracer {

// normalize(v), also when v's squared length would underflow or overflow (an eye 1e-200 from
// its lookat); bit for bit glm::normalize otherwise.
static glm::dvec3 unit(const glm::dvec3& v) {
    const double squared = glm::dot(v, v);
    if (squared > 1e-290 && squared < 1e290) return glm::normalize(v);
    const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    return glm::normalize(v / largest);
}

// The image plane sits at distance 1 whatever the scene's `focal`: the rays through it are
// the same for any distance (only their directions count), so a focal of 1e-300 or 1e300
// gives the same image as 1 instead of underflowing or overflowing.
PinholeCamera::PinholeCamera(const Camera& camera, int width, int height)
    : eye_(camera.eye), focal_(1), width_(width), height_(height) {
    w_ = Vec3(unit(camera.eye - camera.lookat));
    u_ = Vec3(unit(glm::cross(glm::dvec3(camera.up), glm::dvec3(w_))));
    v_ = glm::cross(w_, u_);
    plane_height_ = 2 * focal_ * std::tan(glm::radians(Real(camera.fovy_degrees)) / 2);
    plane_width_ = plane_height_ * Real(width) / Real(height);
    step_x_ = u_ * (plane_width_ / Real(width));
    step_y_ = -v_ * (plane_height_ / Real(height));
    corner_ = -Real(0.5) * plane_width_ * u_ + Real(0.5) * plane_height_ * v_ - focal_ * w_;
}

Ray PinholeCamera::ray_through(Real x, Real y) const {
    Ray ray{eye_, {}};
    row_directions(x, y, 1, &ray.direction);
    return ray;
}

void PinholeCamera::row_directions(Real x_start, Real y, int count, Vec3* out) const {
    constexpr int kChunk = 64;
    Real dx[kChunk], dy[kChunk], dz[kChunk];
    // normalize(corner_ + x step_x_ + y step_y_), written out per component so it vectorises.
    const Vec3 row = y * step_y_;
    for (int start = 0; start < count; start += kChunk) {
        const int n = std::min(kChunk, count - start);
        for (int i = 0; i < n; ++i) {
            const Real x = x_start + Real(start + i);
            dx[i] = (corner_.x + x * step_x_.x) + row.x;
            dy[i] = (corner_.y + x * step_x_.y) + row.y;
            dz[i] = (corner_.z + x * step_x_.z) + row.z;
            const Real inverse_length = Real(1) / std::sqrt(dx[i] * dx[i] + dy[i] * dy[i] + dz[i] * dz[i]);
            dx[i] *= inverse_length, dy[i] *= inverse_length, dz[i] *= inverse_length;
        }
        for (int i = 0; i < n; ++i) out[start + i] = {dx[i], dy[i], dz[i]};
    }
}

bool PinholeCamera::project(const Vec3& point, Real& x, Real& y) const {
    const Vec3 d = point - eye_;
    const Real depth = -glm::dot(d, w_);
    if (!(depth > 0)) return false;
    x = (glm::dot(d, u_) * focal_ / depth / plane_width_ + Real(0.5)) * width_;
    y = (Real(0.5) - glm::dot(d, v_) * focal_ / depth / plane_height_) * height_;
    return true;
}

}  // namespace tracer
