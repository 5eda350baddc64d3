// Ray-triangle intersection (Moller-Trumbore), returning t and the barycentric (u, v) of the
// hit: the point is (1 - u - v) v0 + u v1 + v v2.
#pragma once

#include <glm/geometric.hpp>

#include "render/types.h"

namespace tracer {

struct TriangleHit {
    Real t = 0;
    Real u = 0;
    Real v = 0;
};

// A triangle stored for intersection: one vertex and the two edges leaving it.
struct TriangleEdges {
    Vec3 v0, e1, e2;  // e1 = v1 - v0, e2 = v2 - v0
};

// True, with `hit` filled in, if the ray meets the triangle at t inside `range`. Edges and
// vertices count as inside. No epsilon on the determinant: only an exactly parallel ray (or a
// zero-area triangle) is rejected, so tiny triangles are still found.
inline bool intersect_triangle(const Ray& ray, const TriangleEdges& tri, Interval range, TriangleHit& hit) {
    // Every quantity is computed before one combined test: a miss usually fails one of the
    // early tests at random, and one branch mispredicts less than four.
    const Vec3 p = glm::cross(ray.direction, tri.e2);
    const Real det = glm::dot(tri.e1, p);
    const Real inv_det = 1 / det;
    const Vec3 s = ray.origin - tri.v0;
    const Real u = glm::dot(s, p) * inv_det;
    const Vec3 q = glm::cross(s, tri.e1);
    const Real v = glm::dot(ray.direction, q) * inv_det;
    const Real t = glm::dot(tri.e2, q) * inv_det;
    const bool inside = (det != 0) & (u >= 0) & (u <= 1) & (v >= 0) & (u + v <= 1) & (range.min < t) & (t < range.max);
    if (!inside) return false;
    hit = {t, u, v};
    return true;
}

}  // namespace tracer
