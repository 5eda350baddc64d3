// Boxes around placed shapes, for the world's top level and the solids' leaves: each grown by a
// little more than the roundings of the tests it bounds.
#pragma once

#include <glm/common.hpp>
#include <glm/exponential.hpp>

#include "accel/bvh_search.h"
#include "accel/types.h"
#include "scene/placement.h"

namespace tracer {

// The box around `box` placed by `placement` (its eight corners placed), grown by gamma(16) of
// its coordinates' magnitude: more than the few roundings of placing a corner and of carrying a
// ray into the shape's coordinates.
inline Bounds placed_box(const Bounds& box, const Placement& placement) {
    Bounds out;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 p{(corner & 1 ? box.upper : box.lower).x, (corner & 2 ? box.upper : box.lower).y,
                           (corner & 4 ? box.upper : box.lower).z};
        out.extend(Vec3(placement.point(p)));
    }
    const Vec3 pad =
        gamma(16) * (glm::max(glm::abs(out.lower), glm::abs(out.upper)) + glm::abs(Vec3(placement.translate)));
    return {out.lower - pad, out.upper + pad};
}

// The box around a disc of `radius` at `center` across the unit `axis`: on each coordinate
// radius sqrt(1 - axis_i^2), padded for the slack of the tests at the edges.
inline Bounds disc_box(const glm::dvec3& center, const glm::dvec3& axis, double radius) {
    const glm::dvec3 reach = radius * glm::sqrt(glm::max(glm::dvec3(0.0), 1.0 - axis * axis));
    const glm::dvec3 pad = 1e-6 * radius + double(gamma(64)) * glm::abs(center);
    return Bounds{Vec3(center - reach - pad), Vec3(center + reach + pad)};
}

}  // namespace tracer
