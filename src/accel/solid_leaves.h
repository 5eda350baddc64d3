// The spans (accel/solid_spans.h) of the closed shapes a CSG tree is made of, along a ray's
// whole line (behind its origin too): a sphere, a box, a closed cone and a plane's half-space.
// Each end names the leaf (`surface`) and, for a box or a cone, the face it crosses
// (SpanEnd::part).
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>

#include <glm/geometric.hpp>

#include "accel/round_shapes.h"
#include "accel/solid_spans.h"
#include "accel/types.h"

namespace tracer {

// The sphere's span along the ray's line: its two roots (equal for a tangent line), or none if
// the line misses it. The roots in Haines et al.'s form, as intersect_sphere finds them in a
// double build.
inline std::optional<SolidSpan> sphere_span(const Ray& ray, const Vec3& center, Real radius, uint32_t surface) {
    const Vec3 f = ray.origin - center;
    const Vec3& d = ray.direction;
    const Real a = glm::dot(d, d), b = glm::dot(f, d), c = glm::dot(f, f) - radius * radius;
    const Vec3 f_cross_d = glm::cross(f, d);
    const Real discriminant = a * (radius * radius) - glm::dot(f_cross_d, f_cross_d);
    if (!(discriminant >= 0) || !(a > 0)) return std::nullopt;
    const Real q = -(b + std::copysign(std::sqrt(discriminant), b));
    Real t0 = q != 0 ? c / q : 0, t1 = q / a;  // q = 0: the origin on the sphere, the line tangent
    if (t0 > t1) std::swap(t0, t1);
    return SolidSpan{{t0, surface, false, 0}, {t1, surface, false, 0}};
}

// The box's span along the ray's line (slabs), or none if the line passes outside it; a face is
// numbered 2 axis + (1 for the upper side). A line in a face's plane counts as inside the box.
inline std::optional<SolidSpan> box_span(const Ray& ray, const Vec3& lower, const Vec3& upper, uint32_t surface) {
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
    return SolidSpan{{near, surface, false, near_face}, {far, surface, false, far_face}};
}

// The span of the half-space behind a plane (the side its normal points away from: POV-Ray's
// rule for a plane in CSG), infinite at one end; none if the line runs outside it. A line in the
// plane counts as inside.
inline std::optional<SolidSpan> half_space_span(const Ray& ray, const Vec3& point, const Vec3& normal,
                                                uint32_t surface) {
    const Real height = glm::dot(ray.origin - point, normal), rate = glm::dot(ray.direction, normal);
    if (rate == 0) {
        if (height > 0) return std::nullopt;
        return SolidSpan{{-kInfinity, surface, false, 0}, {kInfinity, surface, false, 0}};
    }
    const Real t = -height / rate;
    if (rate > 0) return SolidSpan{{-kInfinity, surface, false, 0}, {t, surface, false, 0}};
    return SolidSpan{{t, surface, false, 0}, {kInfinity, surface, false, 0}};
}

// The closed cone's span along the ray's line: where the line is both between the caps' planes
// (0 <= h <= height) and within the side (rho <= tip_radius + slope h: the quadratic of
// intersect_cone, <= 0), or none. Its ends are on the side (kConeSide) or a cap (ConePart).
inline std::optional<SolidSpan> cone_span(const Ray& ray, const ConeShape& cone, uint32_t surface) {
    // Step 1: the ray relative to the axis, as intersect_cone has it.
    const Vec3 o = ray.origin - cone.tip;
    const Vec3& d = ray.direction;
    const Vec3& w = cone.axis;
    const Real oz = dot(o, w), dz = dot(d, w);
    const Vec3 op = o - oz * w, dp = d - dz * w;
    // Step 2: between the caps.
    SpanEnd near{-kInfinity, surface, false, uint8_t(kConeSide)}, far{kInfinity, surface, false, uint8_t(kConeSide)};
    if (dz == 0) {
        if (oz < 0 || oz > cone.height) return std::nullopt;
    } else {
        Real t_tip = -oz / dz, t_wide = (cone.height - oz) / dz;
        uint8_t first = uint8_t(kConeTipCap), second = uint8_t(kConeWideCap);
        if (t_tip > t_wide) std::swap(t_tip, t_wide), std::swap(first, second);
        near = {t_tip, surface, false, first};
        far = {t_wide, surface, false, second};
    }
    // Step 3: within the side: a t^2 + 2 b t + c <= 0, its discriminant in intersect_cone's form.
    const Real k = cone.slope;
    const Real radius_here = cone.tip_radius + k * oz;
    const Real a = dot(dp, dp) - k * k * dz * dz;
    const Real b = dot(op, dp) - k * dz * radius_here;
    const Real c = dot(op, op) - radius_here * radius_here;
    const Vec3 moment = glm::cross(o, d);
    const Real across = dot(w, moment);
    const Vec3 e = cone.tip_radius * dp + k * glm::cross(moment, w);
    const Real discriminant = a < 0 ? std::max(dot(e, e) - across * across, Real(0)) : dot(e, e) - across * across;
    Real side_lower = -kInfinity, side_upper = kInfinity;  // the side's stretch of the line
    if (a == 0 && b == 0) {
        if (c > 0) return std::nullopt;  // parallel to the side (or the axis), outside it
    } else if (a == 0) {
        (b > 0 ? side_upper : side_lower) = -c / (2 * b);
    } else {
        if (discriminant < 0) return std::nullopt;
        const Real q = -(b + std::copysign(std::sqrt(discriminant), b));
        Real t0 = q != 0 ? c / q : 0, t1 = q / a;
        if (t0 > t1) std::swap(t0, t1);
        if (a > 0) {
            side_lower = t0, side_upper = t1;
        } else {
            // Steeper than the side: inside before t0 and after t1, on the two nappes of the double
            // cone; the real one (radius not negative) is where the height grows, past the apex.
            if (dz > 0)
                side_lower = t1;
            else
                side_upper = t0;
        }
    }
    // Step 4: the two stretches together.
    if (side_lower > near.t) near = {side_lower, surface, false, uint8_t(kConeSide)};
    if (side_upper < far.t) far = {side_upper, surface, false, uint8_t(kConeSide)};
    if (!(near.t <= far.t)) return std::nullopt;
    return SolidSpan{near, far};
}

}  // namespace tracer
