// A triangle mesh ready for rays: its triangles stored for intersection in BVH leaf order,
// behind the accelerator the scene chose (none, box, median or sah).
#pragma once

#include <cstdint>
#include <vector>

#include "render/bvh.h"
#include "render/mesh_loader.h"
#include "render/triangle.h"

namespace tracer {

struct MeshHit {
    uint32_t triangle = 0;  // index into TriangleMesh::vertices
    uint32_t slot = 0;      // the triangle's place in leaf order, where MeshAccel keeps its data
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

    // Unit face normal (v1 - v0) x (v2 - v0) of a triangle.
    Vec3 geometric_normal(uint32_t triangle) const;
    // Vertex normals interpolated at the hit and renormalised; the face normal where they
    // cancel out.
    Vec3 shading_normal(const MeshHit& hit) const;

    // False only if the ray's line passes outside a sphere around the whole mesh: a few
    // multiplications that spare most rays of a frame the box test's set-up (divisions).
    // Every accelerator but None (every triangle for every ray: always true) asks it first.
    bool may_hit(const Ray& ray) const;

    const TriangleMesh& mesh() const { return mesh_; }
    const Bvh& bvh() const { return bvh_; }
    Accelerator accel() const { return accel_; }
    double build_seconds() const { return build_seconds_; }

private:
    TriangleMesh mesh_;
    Accelerator accel_;
    Bvh bvh_;
    // What shading a hit needs, in leaf order too: read in one or two cache lines, where the
    // mesh's own arrays would cost a cache miss each for a big mesh.
    struct HitRecord {
        Vec3 normals[3];    // the vertex normals
        uint32_t triangle;  // index into mesh_.vertices
    };
    LargeArray<TriangleEdges> edges_;  // entry i is triangle hit_records_[i].triangle
    LargeArray<HitRecord> hit_records_;
    double build_seconds_ = 0;
    Vec3 sphere_centre_{0};
    Real sphere_radius2_ = kInfinity;  // squared (no sphere: every ray passes)
};

}  // namespace tracer
