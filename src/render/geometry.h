// Ray-primitive intersection as pure functions: geometry in, ray parameter out.
// They never return NaN: a miss is std::nullopt, and comparisons are written so that NaN
// inputs fall through to a miss.
#pragma once

#include <optional>

#include "render/types.h"

namespace tracer {

// Nearest t in `range` where `ray` meets the sphere, from outside or inside.
// Uses the discriminant form of Haines et al. (Ray Tracing Gems ch. 7), which stays accurate
// for small spheres far from the ray origin.
std::optional<Real> intersect_sphere(const Ray& ray, const Vec3& center, Real radius, Interval range);

// t in `range` where `ray` meets the infinite plane through `point` with normal `normal`
// (either side); a ray parallel to the plane misses.
std::optional<Real> intersect_plane(const Ray& ray, const Vec3& point, const Vec3& normal, Interval range);

}  // namespace tracer
