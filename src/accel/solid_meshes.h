// Closed meshes as parts of solids (CSG): a mesh's spans along a ray's whole line, from every
// crossing of its surface (MeshAccel::all_hits), inside where the crossings' winding number is
// not zero; and the surface at one of their ends. Crossings closer than the solid's tolerance are
// one place: the two triangles of an edge a ray passes through count once, a ray grazing a
// silhouette edge (in by one triangle, out by the other) not at all.
#pragma once

#include <cstdint>
#include <vector>

#include "accel/mesh_accel.h"
#include "accel/round_shapes.h"
#include "accel/solid_spans.h"
#include "accel/types.h"

namespace tracer {

// A mesh part of a solid: its triangles placed, relative to its solid's shift.
struct SolidMesh {
    MeshAccel accel;
    bool flat = false;  // shaded with each triangle's own normal
};

// The mesh's spans along the ray's line that may matter up to `until` (a span still open there
// ends just past it), each end naming `surface` and whether it enters (part 0) or leaves (1).
void append_mesh_spans(const MeshAccel& mesh, const Ray& ray, Real until, Real tolerance, uint32_t surface,
                       std::vector<SolidSpan>& out);

// The surface where a span of the mesh ends at `t` (`leaving`: its leave end): the point on
// the triangle there, the normal pointing out of the mesh, and the shading normal on its side.
struct MeshSurface {
    RoundSurface round;
    Vec3 shading_normal{0};
};
MeshSurface mesh_span_end_surface(const SolidMesh& mesh, const Ray& ray, Real t, bool leaving, Real tolerance);

}  // namespace tracer
