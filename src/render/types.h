// Basic types of the renderer. `Real` is the precision of all ray arithmetic; one alias so a
// float build can be measured against this double build later.
#pragma once

#include <glm/vec3.hpp>
#include <limits>

namespace tracer {

using Real = double;
using Vec3 = glm::vec<3, Real>;
using Color = glm::dvec3;  // linear RGB, unclamped

constexpr Real kInfinity = std::numeric_limits<Real>::infinity();

struct Ray {
    Vec3 origin;
    Vec3 direction;  // unit length

    Vec3 at(Real t) const { return origin + t * direction; }
};

// An open interval of ray parameters (min, max): hits must lie strictly inside.
struct Interval {
    Real min = 0;
    Real max = kInfinity;

    bool contains(Real t) const { return min < t && t < max; }
};

}  // namespace tracer
