// Cones (cylinders among them) and discs: their ray tests and the surface at a hit, as pure
// inline functions like geometry.h's, with the same rules: no NaN out, a miss is nullopt, and
// the hit point comes with a bound on its rounding error (docs/robustness.md).
//
// A cone is kept in world coordinates by its axis, measured from its narrow end: `tip` (the apex
// of a pointed cone, kept exactly as the scene gives it, so that a ray aimed there meets it), the
// unit `axis` towards the wide end, `height`, the radius at the tip and the `slope` (radius gained
// per unit of height, never negative). A point at height h along the axis and distance rho from
// it is on the side when rho = tip_radius + slope h, 0 <= h <= height.
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
    Vec3 tip;   // the center of the narrow end
    Vec3 axis;  // unit length, from the tip to the wide end
    Real height;
    Real tip_radius;
    Real slope;  // (wide_radius - tip_radius) / height, >= 0
    Real wide_radius;
    bool caps;
};

// The cone from `base` to `top` with these radii, as the world keeps it (measured from the end
// with the smaller radius; the base when they are equal).
inline ConeShape make_cone_shape(const glm::dvec3& base, const glm::dvec3& top, double base_radius, double top_radius,
                                 bool caps) {
    const bool top_is_narrow = top_radius < base_radius;
    const glm::dvec3 tip = top_is_narrow ? top : base, wide_end = top_is_narrow ? base : top;
    const double tip_radius = std::min(base_radius, top_radius), wide_radius = std::max(base_radius, top_radius);
    const double height = glm::length(wide_end - tip);
    return {Vec3(tip),
            Vec3((wide_end - tip) / height),
            Real(height),
            Real(tip_radius),
            Real((wide_radius - tip_radius) / height),
            Real(wide_radius),
            caps};
}

struct DiscShape {
    Vec3 center;
    Vec3 normal;  // unit length
    Real radius;
};

// Which part of a cone a ray met (Hit::primitive): its side, the cap at its tip or at its wide end.
enum ConePart : uint32_t { kConeSide = 0, kConeTipCap = 1, kConeWideCap = 2 };

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
    // Step 1: the ray relative to the axis from the tip: heights (oz, dz) and the parts across it
    // (op, dp); the moment o x d, whose length is the line's distance from the tip (in float with
    // one rounding per component; double's plain cross product was as good on the apex rays).
    const Vec3 o = ray.origin - cone.tip;
    const Vec3& d = ray.direction;
    const Vec3& w = cone.axis;
    const Real oz = dot(o, w), dz = dot(d, w);
    const Vec3 op = o - oz * w, dp = d - dz * w;
    const Vec3 moment = std::is_same_v<Real, float> ? Vec3{difference_of_products(o.y, d.z, o.z, d.y),
                                                           difference_of_products(o.z, d.x, o.x, d.z),
                                                           difference_of_products(o.x, d.y, o.y, d.x)}
                                                    : glm::cross(o, d);
    std::optional<ConeHit> best;
    // Step 2: the side, rho^2 = R(h)^2 with R(h) = tip_radius + slope h, a quadratic in t. Its
    // discriminant b^2 - a c is computed as |R(oz) dp - slope dz op|^2 - (w . (o x d))^2 (the
    // sphere's Lagrange identity, in the plane across the axis), with R(oz) dp - slope dz op =
    // tip_radius dp + slope (o x d) x w: no cancellation for a thin cone far from the ray's
    // origin, and at the apex (tip_radius 0) every term is as small as the moment.
    const Real k = cone.slope;
    const Real radius_here = cone.tip_radius + k * oz;
    const Real a = dot(dp, dp) - k * k * dz * dz;
    const Real b = dot(op, dp) - k * dz * radius_here;
    const Real c = dot(op, op) - radius_here * radius_here;
    const Real across = dot(w, moment);
    const Vec3 e = cone.tip_radius * dp + k * glm::cross(moment, w);
    Real discriminant = dot(e, e) - across * across;
    // A line steeper than the side (a < 0) meets the double cone twice (twice at the apex when it
    // passes through it): its discriminant is never negative, though rounding can make it so.
    if (a < 0) discriminant = std::max(discriminant, Real(0));
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
        cap(0, cone.tip_radius, kConeTipCap);
        cap(cone.height, cone.wide_radius, kConeWideCap);
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
    const Vec3 from_tip = ray.at(t) - cone.tip;
    const Vec3& w = cone.axis;
    Real h = glm::dot(from_tip, w);
    Vec3 across = from_tip - h * w;
    RoundSurface out;
    if (part == kConeSide) {
        const Real length = glm::length(across);
        // On the axis, to the rounding of the projection (the apex, where `across` is noise that
        // need not be across it): any direction across it will do.
        const bool on_axis = length <= gamma(4) * std::abs(h);
        h = std::clamp(h, Real(0), cone.height);
        const Vec3 outward = !on_axis ? across * (1 / length)
                                      : normalize_or_zero(std::abs(w.x) < Real(0.9) ? glm::cross(w, Vec3(1, 0, 0))
                                                                                    : glm::cross(w, Vec3(0, 1, 0)));
        const Real radius = cone.tip_radius + cone.slope * h;
        across = radius * outward;
        out.normal = normalize_or_zero(outward - cone.slope * w);
    } else {
        h = part == kConeWideCap ? cone.height : 0;
        out.normal = part == kConeWideCap ? w : -w;
    }
    const Vec3 along = h * w;
    out.point = cone.tip + along + across;
    // Each coordinate: the roundings of the projection and of the sums (a few ulps of each term).
    out.error = gamma(12) * (abs_each(cone.tip) + abs_each(along) + abs_each(across) + abs_each(from_tip));
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
