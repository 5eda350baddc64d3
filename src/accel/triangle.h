// Ray-triangle intersection, returning t and the barycentric (u, v) of the hit: the point is
// (1 - u - v) v0 + u v1 + v v2. Two tests: the watertight one (Woop, Benthin & Wald 2013), the
// default, and Moller-Trumbore, kept to measure what watertightness costs and buys
// (docs/robustness.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "accel/types.h"

namespace tracer {

// Build-time choice (CMake option TRACER_ROBUST): watertight triangles and error-bounded
// spawn points, or Moller-Trumbore and a fixed t-min of 1e-4 (the first wave's "naive" rules).
#if defined(TRACER_ROBUST) && !TRACER_ROBUST
constexpr bool kRobust = false;
#else
constexpr bool kRobust = true;
#endif

struct TriangleHit {
    Real t = 0;
    Real u = 0;
    Real v = 0;
};

// A triangle stored for intersection: its three vertices, exactly as the mesh holds them, so
// that two triangles sharing an edge see the very same edge.
struct Triangle {
    Vec3 v0, v1, v2;
};

// Component k of p (glm's operator[] is a switch on k).
inline Real component(const Vec3& p, int k) {
    return glm::value_ptr(p)[k];
}

// What the watertight test needs of a ray, worked out once per ray: the axis along which the
// direction is largest becomes z, and the shear that maps the direction to (0, 0, 1).
struct RayShear {
    int kx = 0, ky = 1, kz = 2;
    Real sx = 0, sy = 0, sz = 1;
    Vec3 origin{0};  // the ray's origin, permuted to (kx, ky, kz)
    // A bound on |direction[kx]| and |direction[ky]|, for the error bound of the shear
    // (finish_triangle_hit): 1 for a unit direction, |direction[kz]| otherwise. A ray carried into
    // an instance's coordinates has a direction of length 1 / scale, and with 1 in its place a
    // mesh placed at scale 1e13 lost every hit (its t bound grew with the scale).
    Real shear_error_scale = 1;

    // The shear of `ray`; a zero direction gives a shear that no triangle passes.
    explicit RayShear(const Ray& ray) {
        const Vec3 a = abs_each(ray.direction);
        kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
        kx = kz == 2 ? 0 : kz + 1;
        ky = kx == 2 ? 0 : kx + 1;
        if (ray.direction[kz] < 0) std::swap(kx, ky);  // keeps the winding
        sz = 1 / ray.direction[kz];
        sx = ray.direction[kx] * sz;
        sy = ray.direction[ky] * sz;
        origin = {ray.origin[kx], ray.origin[ky], ray.origin[kz]};
        const Real largest = std::abs(ray.direction[kz]);
        shear_error_scale = largest > Real(0.5) && largest <= 1 ? Real(1) : largest;
    }
};

// A triangle in a ray's frame (see intersect_triangle): its sheared vertices a, b, c, its edge
// functions e0..e2 (the weights of v0..v2 times det) and t times det.
struct ShearedTriangle {
    Real ax, ay, az, bx, by, bz, cx, cy, cz;
    Real e0, e1, e2, det, t_scaled;
    Real shear_error_scale;  // the ray's RayShear::shear_error_scale
};

// How loosely step 3 of the watertight test compares t x det with the range x det: a few ulps,
// so that no t inside the range is lost to the rounding of range x det (finish_triangle_hit
// then tests t itself).
constexpr Real kScaledRangeLoose = 8 * std::numeric_limits<Real>::epsilon();

// Step 3's range test of the watertight test, on a triangle's sheared values: t x det inside
// the range x det, loosely.
inline bool in_scaled_range(const ShearedTriangle& s, Interval range) {
    constexpr Real loose = kScaledRangeLoose;
    const Real abs_det = std::abs(s.det), t_signed = s.det < 0 ? -s.t_scaled : s.t_scaled;
    return (t_signed > range.min * abs_det * (1 - loose)) & (t_signed < range.max * abs_det * (1 + loose));
}

// The hit of a triangle that passed the edge and range tests, unless its t might be <= 0
// within rounding (pbrt-v4's conservative bound on t, from the magnitudes of the sheared
// vertices and edge functions). Out of line: it runs for candidate hits only, and inlined into
// the BVH's loop it slowed every test (measured: docs/robustness.md).
[[gnu::noinline]] inline bool finish_triangle_hit(const ShearedTriangle& s, Interval range, TriangleHit& hit) {
    const Real inv_det = 1 / s.det;
    const Real t = s.t_scaled * inv_det;
    const Real max_z = std::max({std::abs(s.az), std::abs(s.bz), std::abs(s.cz)});
    const Real max_x = std::max({std::abs(s.ax), std::abs(s.bx), std::abs(s.cx)});
    const Real max_y = std::max({std::abs(s.ay), std::abs(s.by), std::abs(s.cy)});
    const Real delta_z = gamma(3) * max_z;
    // The shear's error: |sx z| = |d_kx| |z / d_kz| <= shear_error_scale max_z (pbrt-v4 takes
    // max_z, right for |d| <= 1).
    const Real delta_x = gamma(5) * (max_x + s.shear_error_scale * max_z);
    const Real delta_y = gamma(5) * (max_y + s.shear_error_scale * max_z);
    const Real delta_e = 2 * (gamma(2) * max_x * max_y + delta_y * max_x + delta_x * max_y);
    const Real max_e = std::max({std::abs(s.e0), std::abs(s.e1), std::abs(s.e2)});
    const Real delta_t = 3 * (gamma(3) * max_e * max_z + delta_e * max_z + delta_z * max_e) * std::abs(inv_det);
    if (!(t > delta_t) || !range.contains(t)) return false;
    hit = {t, s.e1 * inv_det, s.e2 * inv_det};
    return true;
}

// Watertight test (Woop, Benthin & Wald 2013): the vertices are moved into the ray's frame
// (origin at 0, direction (0, 0, 1)), and the ray meets the triangle where the 2D point (0, 0)
// lies inside it. Each edge function is evaluated with its exact sign, from the vertices'
// sheared coordinates alone, so the two triangles of a shared edge see the same edge with
// opposite signs: a ray through an edge or a vertex meets at least one of them. (The paper
// recomputes an edge function in double when it is exactly 0; difference_of_products makes
// every sign exact at once.) Hits on an edge or vertex count, from either side; a triangle
// whose sheared projection has zero area (a ray in its plane, or no area) is never hit; and a
// hit whose t might be <= 0 within rounding is refused, so a ray spawned off a surface cannot
// re-hit it behind its origin.
inline bool intersect_triangle(const RayShear& shear, const Triangle& tri, Interval range, TriangleHit& hit) {
    // Step 1: translate, permute, shear (x, y; z only scaled, below).
    ShearedTriangle s;
    s.shear_error_scale = shear.shear_error_scale;
    auto sheared = [&](const Vec3& p, Real& x, Real& y, Real& z) {
        z = component(p, shear.kz) - shear.origin.z;
        x = std::fma(-shear.sx, z, component(p, shear.kx) - shear.origin.x);
        y = std::fma(-shear.sy, z, component(p, shear.ky) - shear.origin.y);
    };
    sheared(tri.v0, s.ax, s.ay, s.az);
    sheared(tri.v1, s.bx, s.by, s.bz);
    sheared(tri.v2, s.cx, s.cy, s.cz);

    // Step 2: the edge functions, with exact signs; (0, 0) inside when they agree.
    s.e0 = difference_of_products(s.cx, s.by, s.cy, s.bx);
    s.e1 = difference_of_products(s.ax, s.cy, s.ay, s.cx);
    s.e2 = difference_of_products(s.bx, s.ay, s.by, s.ax);
    const bool some_negative = (s.e0 < 0) | (s.e1 < 0) | (s.e2 < 0);
    const bool some_positive = (s.e0 > 0) | (s.e1 > 0) | (s.e2 > 0);
    s.det = s.e0 + s.e1 + s.e2;

    // Step 3: t times det, compared with the range times det (no division for a miss); fused
    // explicitly, so that every call site rounds alike (GCC fuses at will otherwise).
    s.az *= shear.sz;
    s.bz *= shear.sz;
    s.cz *= shear.sz;
    s.t_scaled = std::fma(s.e0, s.az, std::fma(s.e1, s.bz, s.e2 * s.cz));
    if ((some_negative & some_positive) | (s.det == 0) | !in_scaled_range(s, range)) return false;
    return finish_triangle_hit(s, range, hit);
}

// Moller-Trumbore's determinant, u, v and t for a ray and a triangle given coordinate by
// coordinate, with R = Real (one triangle) or four vector lanes (triangle_lanes.h), and `fma`
// the fused multiply-add of R: one source for both, every product that meets a sum fused
// explicitly (GCC would fuse at will, differently from one call site to the next), so that both
// round alike (u + v is d.q / det + u, rounded once). Every quantity is computed before one
// combined test (a miss usually fails one of the early tests at random, and one branch
// mispredicts less than four).
template <typename R>
struct MollerTrumboreTerms {
    R det, u, v, t, u_plus_v;
};

template <typename R, typename Fma>
[[gnu::always_inline]] inline MollerTrumboreTerms<R> moller_trumbore_terms(const R (&origin)[3],
                                                                           const R (&direction)[3], const R (&v0)[3],
                                                                           const R (&v1)[3], const R (&v2)[3],
                                                                           Fma fma) {
    const R e1[3] = {v1[0] - v0[0], v1[1] - v0[1], v1[2] - v0[2]};
    const R e2[3] = {v2[0] - v0[0], v2[1] - v0[1], v2[2] - v0[2]};
    const R s[3] = {origin[0] - v0[0], origin[1] - v0[1], origin[2] - v0[2]};
    auto cross = [&](const R(&a)[3], const R(&b)[3], R(&out)[3]) {
        out[0] = fma(a[1], b[2], -(a[2] * b[1]));
        out[1] = fma(a[2], b[0], -(a[0] * b[2]));
        out[2] = fma(a[0], b[1], -(a[1] * b[0]));
    };
    auto dot = [&](const R(&a)[3], const R(&b)[3]) { return fma(a[0], b[0], fma(a[1], b[1], a[2] * b[2])); };
    R p[3], q[3];
    cross(direction, e2, p);
    cross(s, e1, q);
    const R det = dot(e1, p);
    const R inv_det = 1 / det;
    const R u = dot(s, p) * inv_det, d_q = dot(direction, q);
    return {det, u, d_q * inv_det, dot(e2, q) * inv_det, fma(d_q, inv_det, u)};
}

// Whether Moller-Trumbore's terms are a hit inside `range`: a bool, or a mask of lanes.
template <typename R>
[[gnu::always_inline]] inline auto moller_trumbore_inside(const MollerTrumboreTerms<R>& m, Interval range) {
    return (m.det != 0) & (m.u >= 0) & (m.u <= 1) & (m.v >= 0) & (m.u_plus_v <= 1) & (m.t > range.min) &
           (m.t < range.max);
}

// Moller-Trumbore: fewer operations, but not watertight (two triangles sharing an edge can
// both reject a ray through it: hard-cases.md A1, A3, A5). No epsilon on the determinant:
// only an exactly parallel ray (or a zero-area triangle) is rejected, so tiny triangles are
// still found.
inline bool intersect_triangle_moller_trumbore(const Ray& ray, const Triangle& tri, Interval range, TriangleHit& hit) {
    auto coordinates = [](const Vec3& p, Real(&out)[3]) { out[0] = p.x, out[1] = p.y, out[2] = p.z; };
    Real origin[3], direction[3], v0[3], v1[3], v2[3];
    coordinates(ray.origin, origin);
    coordinates(ray.direction, direction);
    coordinates(tri.v0, v0);
    coordinates(tri.v1, v1);
    coordinates(tri.v2, v2);
    const auto fma = [](Real a, Real b, Real c) { return std::fma(a, b, c); };
    const MollerTrumboreTerms<Real> m = moller_trumbore_terms(origin, direction, v0, v1, v2, fma);
    if (!moller_trumbore_inside(m, range)) return false;
    hit = {m.t, m.u, m.v};
    return true;
}

// The test the build chose (kRobust), with the shear it needs worked out per ray.
struct TriangleTester {
    explicit TriangleTester(const Ray& r) : ray(r), shear(r) {}

    bool operator()(const Triangle& tri, Interval range, TriangleHit& hit) const {
        if constexpr (kRobust)
            return intersect_triangle(shear, tri, range, hit);
        else
            return intersect_triangle_moller_trumbore(ray, tri, range, hit);
    }

    Ray ray;
    RayShear shear;
};

}  // namespace tracer
