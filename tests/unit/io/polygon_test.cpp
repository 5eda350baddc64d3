// Triangulating OBJ faces (io/polygon.h): triangles pass through, quads keep both halves facing
// the polygon's way, larger polygons (convex or not) are covered exactly by Earcut's triangles.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "io/polygon.h"

namespace tracer {
namespace {

using Triangles = std::vector<std::array<uint32_t, 3>>;

// Twice the signed area of a triangle of the xy plane (positive: counter-clockwise).
double twice_area(const std::vector<glm::dvec3>& c, const std::array<uint32_t, 3>& t) {
    const glm::dvec3 a = c[t[0]], b = c[t[1]], d = c[t[2]];
    return (b.x - a.x) * (d.y - a.y) - (d.x - a.x) * (b.y - a.y);
}

// Twice the signed area of a polygon of the xy plane (the shoelace formula).
double twice_area(const std::vector<glm::dvec3>& c) {
    double sum = 0;
    for (size_t i = 0; i < c.size(); ++i) {
        const glm::dvec3 a = c[i], b = c[(i + 1) % c.size()];
        sum += a.x * b.y - b.x * a.y;
    }
    return sum;
}

TEST(Polygon, ATrianglePassesThrough) {
    Triangles out;
    ASSERT_TRUE(triangulate_polygon({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, out));
    EXPECT_EQ(out, (Triangles{{0, 1, 2}}));
}

TEST(Polygon, AConcaveQuadIsSplitAlongItsInsideDiagonal) {
    // An arrowhead: corner 3 is the reflex one, so only the diagonal 1-3 stays inside.
    const std::vector<glm::dvec3> corners{{0, 0, 0}, {2, 1, 0}, {0, 2, 0}, {0.5, 1, 0}};
    Triangles out;
    ASSERT_TRUE(triangulate_polygon(corners, out));
    ASSERT_EQ(out.size(), 2u);
    for (const auto& triangle : out) EXPECT_GT(twice_area(corners, triangle), 0) << "a half faces the other way";
    EXPECT_NEAR(twice_area(corners, out[0]) + twice_area(corners, out[1]), twice_area(corners), 1e-12);
}

TEST(Polygon, ANonConvexPolygonIsCoveredExactlyAndWoundAsWritten) {
    // An L of six corners, written clockwise: n - 2 triangles, each clockwise too, their areas
    // adding up to the polygon's.
    const std::vector<glm::dvec3> corners{{0, 0, 0}, {0, 2, 0}, {1, 2, 0}, {1, 1, 0}, {2, 1, 0}, {2, 0, 0}};
    Triangles out;
    ASSERT_TRUE(triangulate_polygon(corners, out));
    ASSERT_EQ(out.size(), corners.size() - 2);
    double sum = 0;
    for (const auto& triangle : out) {
        EXPECT_LT(twice_area(corners, triangle), 0);
        sum += twice_area(corners, triangle);
    }
    EXPECT_NEAR(sum, twice_area(corners), 1e-12);
}

TEST(Polygon, APolygonOffTheAxisPlanesIsTriangulatedOnItsDominantPlane) {
    // A regular pentagon turned out of every axis plane.
    std::vector<glm::dvec3> corners;
    const glm::dvec3 u = glm::normalize(glm::dvec3(1, 1, 0)), v = glm::normalize(glm::dvec3(-1, 1, 2));
    for (int i = 0; i < 5; ++i) {
        const double angle = 2 * M_PI * i / 5;
        corners.push_back(std::cos(angle) * u + std::sin(angle) * v + glm::dvec3(3, -2, 7));
    }
    Triangles out;
    ASSERT_TRUE(triangulate_polygon(corners, out));
    EXPECT_EQ(out.size(), 3u);
    const glm::dvec3 facing = glm::cross(u, v);
    for (const auto& t : out)
        EXPECT_GT(glm::dot(glm::cross(corners[t[1]] - corners[t[0]], corners[t[2]] - corners[t[0]]), facing), 0);
}

}  // namespace
}  // namespace tracer
