// Basic types of the renderer. `Real` is the precision of all ray arithmetic: double, or float
// in a build made to measure what double buys (docs/bench/speed-vs-error.md).
#pragma once

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace tracer {

#if defined(TRACER_REAL_FLOAT) && TRACER_REAL_FLOAT
using Real = float;  // CMake: -DTRACER_REAL=float
#else
using Real = double;
#endif
using Vec3 = glm::vec<3, Real>;
using Mat3 = glm::mat<3, 3, Real>;
using Color = glm::dvec3;  // linear RGB, unclamped

constexpr Real kInfinity = std::numeric_limits<Real>::infinity();

// n u / (1 - n u), u the unit roundoff: bounds the relative error of n successive roundings
// (pbrt-v4's gamma), for the error bounds of hit points and triangle t.
constexpr Real gamma(int n) {
    constexpr Real u = std::numeric_limits<Real>::epsilon() / 2;
    return n * u / (1 - n * u);
}

// |v| coordinate by coordinate: glm::abs, always inlined : GCC left glm's out of line in the
// shading loop, a call per use (docs/bench/code-figures.md).
[[gnu::always_inline]] inline Vec3 abs_each(const Vec3& v) {
    return {std::abs(v.x), std::abs(v.y), std::abs(v.z)};
}

// glm::dot, always inlined: GCC called glm's from the cone test (docs/bench/code-figures.md).
// The same sum as glm's, in the same order.
[[gnu::always_inline]] inline Real dot(const Vec3& a, const Vec3& b) {
    const Vec3 products = a * b;
    return products.x + products.y + products.z;
}

struct Ray {
    Vec3 origin;
    Vec3 direction;  // unit length

    Vec3 at(Real t) const { return origin + t * direction; }
};

// `v` scaled to unit length, or the zero vector when it has no direction (zero, or so large or
// small that its length is not a finite positive number).
inline Vec3 normalize_or_zero(const Vec3& v) {
    const Real length = glm::length(v);
    return length > 0 && std::isfinite(length) ? v / length : Vec3(0);
}

// a b - c d with a relative error of at most 2 ulp (Kahan's algorithm with fused
// multiply-adds; Jeannerod et al. 2013), so its sign is the exact sign, and it is exactly 0
// only when a b = c d exactly.
inline Real difference_of_products(Real a, Real b, Real c, Real d) {
    const Real cd = c * d;
    const Real error = std::fma(-c, d, cd);  // cd - c d, exactly
    return std::fma(a, b, -cd) + error;
}

// An open interval of ray parameters (min, max): hits must lie strictly inside.
struct Interval {
    Real min = 0;
    Real max = kInfinity;

    bool contains(Real t) const { return min < t && t < max; }
};

}  // namespace tracer
