// The triangles of the finite flat shapes (scene.h's FlatTriangle, Quad and Box) in their own
// coordinates, before placing: what the world builds them from and the validator checks.
#pragma once

#include "scene/scene.h"
#include "scene/triangle_mesh.h"

namespace tracer {

// Each also has surface coordinates (u, v): a triangle's (0, 0) at a, (1, 0) at b, (0, 1) at c;
// a quad's (0, 0) at `corner`, (1, 0) at corner + edge1, (0, 1) at corner + edge2; a box's per
// face, 0..1 across it, seen from outside with y up on the sides (u towards +x on the +z face,
// -x on -z, -z on +x, +z on -x) and with -z up on the top (+z up on the bottom), u towards +x.

// One triangle a, b, c.
TriangleMesh triangle_mesh(const FlatTriangle& shape);
// Two triangles sharing the diagonal from `corner` to `corner + edge1 + edge2`, wound like the quad.
TriangleMesh triangle_mesh(const Quad& shape);
// Twelve triangles over the eight corners, each face wound so that its normal points outwards.
TriangleMesh triangle_mesh(const Box& shape);

}  // namespace tracer
