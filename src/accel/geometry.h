// Ray-primitive intersection as pure functions: geometry in, ray parameter out. Defined here,
// inline, because they are the innermost loop of every ray.
// They never return NaN: a miss is std::nullopt, and comparisons are written so that NaN
// inputs fall through to a miss.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>

#include <glm/geometric.hpp>

#include "accel/types.h"

namespace tracer {

// The margin of line_may_meet_sphere for the rounding of its difference, relative to the
// center's squared distance: 10^-12 in double, 16 ulps in float (where 10^-12 is below the
// rounding: a thin cylinder 10^4 away was culled).
constexpr Real kLineMargin = std::max<Real>(Real(1e-12), 16 * std::numeric_limits<Real>::epsilon());

// False only if the ray's line passes outside the sphere of squared radius `radius2`: the
// squared distance of the center from the line, times |d|^2 (no division), against r^2 with a
// margin (10^-6 r^2, and kLineMargin of the center's squared distance, for its rounding); a NaN
// counts as "may meet".
[[gnu::always_inline]] inline bool line_may_meet_sphere(const Ray& ray, const Vec3& center, Real radius2) {
    const Vec3 to_center = center - ray.origin;
    const Real along = glm::dot(to_center, ray.direction);
    const Real dd = glm::dot(ray.direction, ray.direction), cc = glm::dot(to_center, to_center);
    return !(cc * dd - along * along > (radius2 * (1 + 1e-6) + cc * kLineMargin) * dd);
}

// Nearest t in `range` where `ray` meets the sphere, from outside or inside.
// Uses the discriminant form of Haines et al. (Ray Tracing Gems ch. 7), which stays accurate
// for small spheres far from the ray origin.
[[gnu::always_inline]] inline std::optional<Real> intersect_sphere(const Ray& ray, const Vec3& center, Real radius,
                                                                   Interval range) {
    const Vec3 f = ray.origin - center;
    const Vec3& d = ray.direction;
    const Real b = glm::dot(f, d);  // half of the usual b
    const Real c = glm::dot(f, f) - radius * radius;
    // Origin outside (c > 0) and moving away (b > 0): both roots are negative. Most rays
    // leave here, without a division.
    if (c > 0 && b > 0) return std::nullopt;
    const Real a = glm::dot(d, d);
    // b^2 - ac computed as a r^2 - |f x d|^2 (Lagrange's identity; Haines et al.'s
    // a (r^2 - |f - (b/a) d|^2)): no cancellation when the sphere is small and far away. In
    // float each component of the cross product is a difference of products with an exact sign
    // (hard-cases.md's C1 misses 10 rays without); double's plain products are close enough.
    const Vec3 f_cross_d = std::is_same_v<Real, float> ? Vec3{difference_of_products(f.y, d.z, f.z, d.y),
                                                              difference_of_products(f.z, d.x, f.x, d.z),
                                                              difference_of_products(f.x, d.y, f.y, d.x)}
                                                       : glm::cross(f, d);
    const Real discriminant = a * (radius * radius) - glm::dot(f_cross_d, f_cross_d);
    if (!(discriminant >= 0)) return std::nullopt;
    // The root with the larger magnitude first (no cancellation), the other from t0 t1 = c/a.
    const Real q = -(b + std::copysign(std::sqrt(discriminant), b));
    if (q == 0) return std::nullopt;  // origin on the surface, ray tangent: t = 0 twice
    Real t0 = c / q, t1 = q / a;
    if (t0 > t1) std::swap(t0, t1);
    if (range.contains(t0)) return t0;
    if (range.contains(t1)) return t1;
    return std::nullopt;
}

// t in `range` where `ray` meets the infinite plane through `point` with normal `normal`
// (either side); a ray parallel to the plane misses.
[[gnu::always_inline]] inline std::optional<Real> intersect_plane(const Ray& ray, const Vec3& point, const Vec3& normal,
                                                                  Interval range) {
    const Real denominator = glm::dot(normal, ray.direction);
    if (denominator == 0) return std::nullopt;
    const Real t = glm::dot(point - ray.origin, normal) / denominator;
    if (range.contains(t)) return t;
    return std::nullopt;
}

}  // namespace tracer
