// Where a placed shape's own coordinates go in the world (scene.h's Placed: scale, rotate,
// translate, then the transform block's steps) as one affine map in double. Normals map by the
// inverse transpose; a map with a negative determinant mirrors.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include "scene/scene.h"

namespace tracer {

struct Placement {
    glm::dmat3 linear{1.0};  // scales and rotations
    glm::dmat3 normal{1.0};  // inverse transpose of `linear`
    glm::dvec3 translate{0.0};

    Placement() = default;  // the identity: the shape's own coordinates
    explicit Placement(const Placed& placed) {
        then_scale(placed.scale);
        then_rotate(placed.rotate_axis, placed.rotate_degrees);
        translate += placed.translate;
        for (const TransformStep& step : placed.steps) {
            if (step.kind == TransformStep::Kind::Scale) then_scale(step.vector);
            if (step.kind == TransformStep::Kind::Rotate) then_rotate(step.vector, step.degrees);
            if (step.kind == TransformStep::Kind::Translate) translate += step.vector;
        }
        normal = glm::transpose(glm::inverse(linear));
    }

    // A point of the shape, placed in the world (in double, whatever Real is).
    glm::dvec3 point(const glm::dvec3& p) const { return linear * p + translate; }
    // The largest coordinate magnitude a point with every coordinate within +-largest can have
    // once placed.
    double reach(double largest) const {
        double most = 0;
        for (int row = 0; row < 3; ++row) {
            double sum = std::abs(translate[row]);
            for (int column = 0; column < 3; ++column) sum += std::abs(linear[column][row]) * largest;
            most = std::max(most, sum);
        }
        return most;
    }
    // True if the map turns space inside out (an odd number of negative scale factors).
    bool mirrors() const { return glm::determinant(linear) < 0; }

private:
    void then(const glm::dmat3& map) {
        linear = map * linear;
        translate = map * translate;
    }
    void then_scale(const glm::dvec3& factors) {
        glm::dmat3 scale(1.0);
        for (int i = 0; i < 3; ++i) scale[i][i] = factors[i];
        then(scale);
    }
    void then_rotate(const glm::dvec3& axis, double degrees) {
        if (degrees != 0) then(glm::dmat3(glm::rotate(glm::dmat4(1.0), glm::radians(degrees), axis)));
    }
};

// Why a shape (`what`: "mesh", "quad", ...) whose placed coordinates reach `reach` cannot be
// rendered, or "" when it lies within +-kLargestMagnitude.
inline std::string placed_reach_problem(std::string_view what, double reach) {
    if (reach <= kLargestMagnitude) return "";
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", reach);
    return "this " + std::string(what) + ", scaled and moved, reaches coordinates up to " + text +
           ", beyond +-1e30 (the renderer keeps bounding boxes in float and squares and cubes lengths)";
}

}  // namespace tracer
