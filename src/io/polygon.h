// Triangulating an OBJ face: triangles pass through, quads split along the diagonal that
// keeps both halves facing the polygon's way, larger polygons (convex or not) go to Mapbox's
// Earcut on the polygon's dominant plane.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace tracer {

// Appends the triangles of the polygon whose corners are `corners` (positions in order,
// either winding) as triples of corner numbers 0..n-1, each wound as the polygon is. Returns
// false if Earcut could not cover the polygon (it self-intersects): then the triangles found
// are appended and the rest of the polygon is missing.
bool triangulate_polygon(const std::vector<glm::dvec3>& corners, std::vector<std::array<uint32_t, 3>>& out);

}  // namespace tracer
