// The triangles of the finite flat shapes (scene.h's FlatTriangle, Quad and Box) in their own
// coordinates, before placing: what the world builds them from and the validator checks.
#pragma once

#include "scene/scene.h"
#include "scene/triangle_mesh.h"

namespace tracer {

// One triangle a, b, c.
TriangleMesh triangle_mesh(const FlatTriangle& shape);
// Two triangles sharing the diagonal from `corner` to `corner + edge1 + edge2`, wound like the quad.
TriangleMesh triangle_mesh(const Quad& shape);
// Twelve triangles over the eight corners, each face wound so that its normal points outwards.
TriangleMesh triangle_mesh(const Box& shape);

}  // namespace tracer
