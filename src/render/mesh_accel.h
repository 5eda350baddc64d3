// A triangle mesh ready for rays: its triangles in BVH leaf order (for intersection and for
// shading), behind the accelerator the scene chose (none, box, median or sah).
#pragma once

#include <cstdint>
#include <vector>

#include "render/bvh.h"
#include "render/mesh_loader.h"
#include "render/triangle.h"

namespace tracer {

struct MeshHit {
    uint32_t triangle = 0;  // the triangle's number in the mesh as loaded
    uint32_t slot = 0;      // its number in leaf order: an index into MeshAccel::mesh().vertices
    TriangleHit hit;
};

class MeshAccel {
public:
    // Builds the accelerator on `threads` threads (0: one per core).
    MeshAccel(TriangleMesh mesh, Accelerator accel, int leaf_size, int threads = 0);

    // The nearest triangle with t inside `range`; shrinks range.max to it.
    bool intersect(const Ray& ray, Interval& range, MeshHit& out, TraversalCounts& counts) const;
    // True if any triangle lies along the ray inside `range`.
    bool occluded(const Ray& ray, Interval range, TraversalCounts& counts) const;

    // Unit face normal (v1 - v0) x (v2 - v0) of the triangle in leaf slot `slot`.
    Vec3 geometric_normal(uint32_t slot) const;
    // Vertex normals interpolated at the hit and renormalised; the face normal where they
    // cancel out.
    Vec3 shading_normal(const MeshHit& hit) const;

    // The mesh, its triangles in leaf order (slot i is the loaded mesh's triangle
    // triangle_id(i)) and its vertex normals renumbered in order of first use.
    const TriangleMesh& mesh() const { return mesh_; }
    uint32_t triangle_id(uint32_t slot) const { return ids_[slot]; }
    const Bvh& bvh() const { return bvh_; }
    Accelerator accel() const { return accel_; }
    double build_seconds() const { return build_seconds_; }

private:
    // False only if the ray's line passes outside a sphere around the whole mesh: a few
    // multiplications that spare most rays of a frame the box test's set-up (divisions).
    // Every accelerator but None (every triangle for every ray) asks it first.
    bool may_hit(const Ray& ray) const;

    TriangleMesh mesh_;
    Accelerator accel_;
    Bvh bvh_;
    LargeArray<TriangleEdges> edges_;  // by leaf slot
    std::vector<uint32_t> ids_;        // leaf slot -> triangle number in the loaded mesh
    double build_seconds_ = 0;
    Vec3 sphere_centre_{0};
    Real sphere_radius2_ = kInfinity;  // squared, with a margin (no sphere: every ray passes)
};

}  // namespace tracer
