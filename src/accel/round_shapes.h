// Cones (cylinders among them) and discs: their ray tests and the surface at a hit, as pure
// inline functions like geometry.h's, with the same rules: no NaN out, a miss is nullopt, and
// the hit point comes with a bound on its rounding error (docs/robustness.md).
//
// A cone is kept in world coordinates by its axis: `base`, the unit `axis`, `height`, the radius
// at the base and the `slope` (radius gained per unit of height). A point at height h along the
// axis and distance rho from it is on the side when rho = base_radius + slope h, 0 <= h <= height.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <type_traits>

#include <glm/geometric.hpp>

#include "accel/types.h"

namespace tracer {

struct ConeShape {
    Vec3 base;
    Vec3 axis;  // unit length, from base to top
    Real height;
    Real base_radius;
    Real slope;  // (top_radius - base_radius) / height
    Real top_radius;
    bool caps;
};

struct DiscShape {
    Vec3 center;
    Vec3 normal;  // unit length
    Real radius;
};

// Which part of a cone a ray met (Hit::primitive).
enum ConePart : uint32_t { kConeSide = 0, kConeBaseCap = 1, kConeTopCap = 2 };

struct ConeHit {
    Real t;
    uint32_t part;
};

// The slack of a test at the edge between a cone's side and a cap, relative to the lengths
// involved: each test accepts a little beyond the edge, so that no ray slips between the two.
// (Less than half the hit point's error bound, so that a ray spawned off a cap clears the side's
// slack.)
constexpr Real kEdgeSlack = gamma(6);

// Nearest t in `range` where `ray` meets the cone (its side, and its caps if it has them).
[[gnu::always_inline]] inline std::optional<ConeHit> intersect_cone(const Ray& ray, const ConeShape& cone,
                                                                    Interval range) {
    // Step 1: the ray relative to the axis: heights (oz, dz) and the parts across it (op, dp).
    const Vec3 o = ray.origin - cone.base;
    const Vec3& d = ray.direction;
    const Vec3& w = cone.axis;
    const Real oz = dot(o, w), dz = dot(d, w);
    const Vec3 op = o - oz * w, dp = d - dz * w;
    std::optional<ConeHit> best;
    // Step 2: the side, rho^2 = R(h)^2 with R(h) = base_radius + slope h, a quadratic in t. Its
    // discriminant b^2 - a c is computed as |R(oz) dp - slope dz op|^2 - (w . (o x d))^2 (the
    // sphere's Lagrange identity, in the plane across the axis): no cancellation for a thin cone
    // far from the ray's origin.
    const Real k = cone.slope;
    const Real radius_here = cone.base_radius + k * oz;
    const Real a = dot(dp, dp) - k * k * dz * dz;
    const Real b = dot(op, dp) - k * dz * radius_here;
    const Real c = dot(op, op) - radius_here * radius_here;
    const Vec3 o_cross_d = std::is_same_v<Real, float> ? Vec3{difference_of_products(o.y, d.z, o.z, d.y),
                                                              difference_of_products(o.z, d.x, o.x, d.z),
                                                              difference_of_products(o.x, d.y, o.y, d.x)}
                                                       : glm::cross(o, d);
    const Real across = dot(w, o_cross_d);
    const Vec3 e = radius_here * dp - k * dz * op;
    const Real discriminant = dot(e, e) - across * across;
    if (discriminant >= 0) {
        // The root with the larger magnitude first (no cancellation), the other from t0 t1 = c/a;
        // a ray along the slope (a = 0) gets its one root as c/q.
        const Real q = -(b + std::copysign(std::sqrt(discriminant), b));
        if (q != 0) {
            Real t0 = c / q, t1 = q / a;
            if (!(t0 <= t1)) std::swap(t0, t1);
            for (Real t : {t0, t1}) {
                if (!range.contains(t)) continue;
                const Real h = oz + t * dz;
                const Real slack = kEdgeSlack * (std::abs(oz) + std::abs(t * dz));
                if (h >= -slack && h <= cone.height + slack) {
                    best = ConeHit{t, kConeSide};
                    range.max = t;
                    break;
                }
            }
        }
    }
    // Step 3: the caps, each a disc across the axis.
    if (cone.caps && dz != 0) {
        auto cap = [&](Real h, Real radius, uint32_t part) {
            if (radius == 0) return;
            const Real t = (h - oz) / dz;
            if (!range.contains(t)) return;
            const Vec3 p = op + t * dp;
            const Real extent = std::abs(p.x) + std::abs(p.y) + std::abs(p.z);
            const Real most = radius + kEdgeSlack * (extent + std::abs(op.x) + std::abs(op.y) + std::abs(op.z));
            if (dot(p, p) <= most * most) {
                best = ConeHit{t, part};
                range.max = t;
            }
        };
        cap(0, cone.base_radius, kConeBaseCap);
        cap(cone.height, cone.top_radius, kConeTopCap);
    }
    return best;
}

// t in `range` where `ray` meets the disc (either side).
[[gnu::always_inline]] inline std::optional<Real> intersect_disc(const Ray& ray, const DiscShape& disc,
                                                                 Interval range) {
    const Real denominator = glm::dot(disc.normal, ray.direction);
    if (denominator == 0) return std::nullopt;
    const Vec3 to_center = disc.center - ray.origin;
    const Real t = glm::dot(to_center, disc.normal) / denominator;
    if (!range.contains(t)) return std::nullopt;
    const Vec3 p = t * ray.direction - to_center;
    if (!(glm::dot(p, p) <= disc.radius * disc.radius)) return std::nullopt;
    return t;
}

// The surface of a cone where `ray` met `part` at `t`: the point put back on the surface (as a
// sphere's is), its error bound, and the outward normal (the same for shading and spawning).
struct RoundSurface {
    Vec3 point, normal, error;
};

inline RoundSurface cone_surface(const Ray& ray, const ConeShape& cone, Real t, uint32_t part) {
    const Vec3 from_base = ray.at(t) - cone.base;
    const Vec3& w = cone.axis;
    Real h = glm::dot(from_base, w);
    Vec3 across = from_base - h * w;
    RoundSurface out;
    if (part == kConeSide) {
        h = std::clamp(h, Real(0), cone.height);
        const Real length = glm::length(across);
        // On the axis (a point of the cone, met head on): any direction across it will do.
        const Vec3 outward = length > 0 ? across * (1 / length)
                                        : normalize_or_zero(std::abs(w.x) < Real(0.9) ? glm::cross(w, Vec3(1, 0, 0))
                                                                                      : glm::cross(w, Vec3(0, 1, 0)));
        const Real radius = cone.base_radius + cone.slope * h;
        across = radius * outward;
        out.normal = normalize_or_zero(outward - cone.slope * w);
    } else {
        h = part == kConeTopCap ? cone.height : 0;
        out.normal = part == kConeTopCap ? w : -w;
    }
    const Vec3 along = h * w;
    out.point = cone.base + along + across;
    // Each coordinate: the roundings of the projection and of the sums (a few ulps of each term).
    out.error = gamma(12) * (abs_each(cone.base) + abs_each(along) + abs_each(across) + abs_each(from_base));
    return out;
}

// The surface of a disc at the hit `t` of `ray`: the point projected onto its plane.
inline RoundSurface disc_surface(const Ray& ray, const DiscShape& disc, Real t) {
    const Vec3 along_ray = ray.at(t);
    RoundSurface out;
    out.point = along_ray - glm::dot(along_ray - disc.center, disc.normal) * disc.normal;
    out.error = gamma(8) * (abs_each(out.point) + abs_each(disc.center));
    out.normal = disc.normal;
    return out;
}

}  // namespace tracer
