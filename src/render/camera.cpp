#include "render/camera.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace tracer {

PinholeCamera::PinholeCamera(const Camera& camera, int width, int height)
    : eye_(camera.eye), focal_(camera.focal), width_(width), height_(height) {
    w_ = glm::normalize(Vec3(camera.eye - camera.lookat));
    u_ = glm::normalize(glm::cross(Vec3(camera.up), w_));
    v_ = glm::cross(w_, u_);
    plane_height_ = 2 * focal_ * std::tan(glm::radians(Real(camera.fovy_degrees)) / 2);
    plane_width_ = plane_height_ * Real(width) / Real(height);
}

Ray PinholeCamera::ray_through(Real x, Real y) const {
    const Real px = (x / width_ - Real(0.5)) * plane_width_;
    const Real py = (Real(0.5) - y / height_) * plane_height_;
    return {eye_, glm::normalize(px * u_ + py * v_ - focal_ * w_)};
}

}  // namespace tracer
