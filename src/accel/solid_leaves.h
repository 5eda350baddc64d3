// The spans (accel/solid_spans.h) of the closed shapes a CSG tree is made of, along a ray's
// whole line (behind its origin too): a sphere, a box and a plane's half-space. Each end names
// the leaf (`surface`) and, for a box, the face it crosses (SpanEnd::part). Not yet used by the
// world (issue 55).
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>

#include <glm/geometric.hpp>

#include "accel/solid_spans.h"
#include "accel/types.h"

namespace tracer {

// The sphere's span along the ray's line: its two roots (equal for a tangent line), or none if
// the line misses it. The roots in Haines et al.'s form, as intersect_sphere finds them in a
// double build.
inline std::optional<Span> sphere_span(const Ray& ray, const Vec3& center, Real radius, uint32_t surface) {
    const Vec3 f = ray.origin - center;
    const Vec3& d = ray.direction;
    const Real a = glm::dot(d, d), b = glm::dot(f, d), c = glm::dot(f, f) - radius * radius;
    const Vec3 f_cross_d = glm::cross(f, d);
    const Real discriminant = a * (radius * radius) - glm::dot(f_cross_d, f_cross_d);
    if (!(discriminant >= 0) || !(a > 0)) return std::nullopt;
    const Real q = -(b + std::copysign(std::sqrt(discriminant), b));
    Real t0 = q != 0 ? c / q : 0, t1 = q / a;  // q = 0: the origin on the sphere, the line tangent
    if (t0 > t1) std::swap(t0, t1);
    return Span{{t0, surface, false, 0}, {t1, surface, false, 0}};
}

// The box's span along the ray's line (slabs), or none if the line passes outside it; a face is
// numbered 2 axis + (1 for the upper side). A line in a face's plane counts as inside the box.
inline std::optional<Span> box_span(const Ray& ray, const Vec3& lower, const Vec3& upper, uint32_t surface) {
    Real near = -kInfinity, far = kInfinity;
    uint8_t near_face = 0, far_face = 1;
    for (int axis = 0; axis < 3; ++axis) {
        const Real d = ray.direction[axis], o = ray.origin[axis];
        if (d == 0) {
            if (o < lower[axis] || o > upper[axis]) return std::nullopt;
            continue;
        }
        Real t_lower = (lower[axis] - o) / d, t_upper = (upper[axis] - o) / d;
        uint8_t enter_face = uint8_t(2 * axis), leave_face = uint8_t(2 * axis + 1);
        if (t_lower > t_upper) std::swap(t_lower, t_upper), std::swap(enter_face, leave_face);
        if (t_lower > near) near = t_lower, near_face = enter_face;
        if (t_upper < far) far = t_upper, far_face = leave_face;
    }
    if (!(near <= far)) return std::nullopt;
    return Span{{near, surface, false, near_face}, {far, surface, false, far_face}};
}

// The span of the half-space behind a plane (the side its normal points away from: POV-Ray's
// rule for a plane in CSG), infinite at one end; none if the line runs outside it. A line in the
// plane counts as inside.
inline std::optional<Span> half_space_span(const Ray& ray, const Vec3& point, const Vec3& normal, uint32_t surface) {
    const Real height = glm::dot(ray.origin - point, normal), rate = glm::dot(ray.direction, normal);
    if (rate == 0) {
        if (height > 0) return std::nullopt;
        return Span{{-kInfinity, surface, false, 0}, {kInfinity, surface, false, 0}};
    }
    const Real t = -height / rate;
    if (rate > 0) return Span{{-kInfinity, surface, false, 0}, {t, surface, false, 0}};
    return Span{{t, surface, false, 0}, {kInfinity, surface, false, 0}};
}

}  // namespace tracer
