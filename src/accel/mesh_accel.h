// A triangle mesh ready for rays: its triangles stored for intersection in BVH leaf order,
// behind the accelerator the scene chose (every triangle, or a BVH built by box, median or
// sah). Built once per mesh file, in the file's coordinates, and shared by every instance of
// it; or built placed in the world from one or several mesh blocks merged (see world.h).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "accel/bvh.h"
#include "accel/triangle.h"
#include "accel/triangle_lanes.h"
#include "scene/placement.h"
#include "scene/triangle_mesh.h"

namespace tracer {

// How a mesh's (or the world's) triangles are searched.
struct SearchSettings {
    bool brute_force = false;  // test every primitive for every ray (no BVH)
    BvhBuild build = BvhBuild::Sah;
    int leaf_size = 4;
    int threads = 0;        // build threads (0: one per core)
    bool keep_uvs = false;  // keep each triangle's surface coordinates (a pattern maps by them)
};

// Triangles in slots first .. first + count - 1.
struct TriangleRun {
    uint32_t first = 0;
    uint32_t count = 0;
};

struct MeshHit {
    uint32_t slot = 0;  // the triangle's place in leaf order, where MeshAccel keeps its data
    TriangleHit hit;
};

// A file's triangles placed by `placement`, marked with `tag` (World: the mesh block's object).
struct MeshPart {
    const TriangleMesh* file;
    Placement placement;
    uint32_t tag = 0;
    bool flat = false;  // each triangle shaded with its own normal
};

// Parts placed and put together, as in one file: what a MeshAccel is built from.
struct PlacedTriangles {
    static constexpr uint32_t kFlat = ~uint32_t(0);  // a normal id: shaded with its face normal
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;
    std::vector<std::array<uint32_t, 3>> triangles;  // indices into positions
    // Per triangle: indices into normals, or kFlat (all three); empty while every triangle is flat.
    std::vector<std::array<uint32_t, 3>> normal_ids;
    std::vector<uint32_t> tags;     // per triangle: its part's tag
    std::vector<uint32_t> numbers;  // per triangle: its number in its part's file
    // Per triangle, when `keep_uvs`: its corners' surface coordinates ((0, 0) where its file has none).
    bool keep_uvs = false;
    std::vector<std::array<glm::vec2, 3>> uvs;

    // Room for this many more positions, normals and triangles.
    void reserve_more(size_t positions, size_t normals, size_t triangles);
};

// Appends `part` placed, with its vertex normals: none if flat (each triangle shaded with its
// face normal), the file's placed by the inverse transpose, else area-weighted over the placed
// triangles.
void append_part(PlacedTriangles& out, const MeshPart& part, int threads);
// The parts placed (append_part), with room for flat parts of this many more positions and
// triangles to be appended.
PlacedTriangles place(const std::vector<MeshPart>& parts, int threads, size_t flat_positions = 0,
                      size_t flat_triangles = 0, bool keep_uvs = false);

class MeshAccel {
public:
    // The triangles behind one accelerator; `mesh` is emptied as the build goes, to keep the
    // peak memory near the result's.
    MeshAccel(PlacedTriangles&& mesh, const SearchSettings& settings);
    // The parts' triangles, placed (append_part), behind one accelerator.
    MeshAccel(const std::vector<MeshPart>& parts, const SearchSettings& settings);
    // One file, placed.
    MeshAccel(const TriangleMesh& file, const Placement& placement, const SearchSettings& settings, bool flat = false)
        : MeshAccel(std::vector<MeshPart>{{&file, placement, 0, flat}}, settings) {}

    // The nearest triangle with t inside `range`; shrinks range.max to it.
    bool intersect(const Ray& ray, Interval& range, MeshHit& out, TraversalCounts& counts) const;
    // intersect for each of *rays[0 .. count) (count at most kPacket), traced together where
    // they allow it (accel/ray_packet.h): the same answers. Bit i of the result is set if ray i
    // hit; out[i] and ranges[i] are then its hit and its range shrunk to it.
    unsigned intersect_packet(const Ray* const* rays, int count, Interval* ranges, MeshHit* out,
                              TraversalCounts& counts) const;
    // Appends to `out` every triangle along the ray inside `range`, in no particular order (the
    // crossings of a closed mesh that is part of a solid: accel/solid_meshes.h).
    void all_hits(const Ray& ray, Interval range, std::vector<MeshHit>& out, TraversalCounts& counts) const;
    // True if any triangle lies along the ray inside `range`; `blocker` is then the run of at
    // most kTriangleLanes triangles tested together that holds one.
    bool occluded(const Ray& ray, Interval range, TraversalCounts& counts, TriangleRun& blocker) const;
    bool occluded(const Ray& ray, Interval range, TraversalCounts& counts) const {
        TriangleRun blocker;
        return occluded(ray, range, counts, blocker);
    }
    // True if a triangle of `run` lies along the ray inside `range` (the test occluded makes).
    bool blocks(TriangleRun run, const Ray& ray, Interval range) const;
    // occluded among the triangles of leaves[0 .. count) alone (runs of any length); `blocker`
    // is then the run of at most kTriangleLanes triangles tested together that holds one.
    bool leaves_block(const TriangleRun* leaves, int count, const Ray& ray, Interval range, TraversalCounts& counts,
                      TriangleRun& blocker) const;
    // The triangle in `slot`, as the mesh places it.
    Triangle triangle(uint32_t slot) const { return columns().triangle(slot); }

    // The point at barycentric (u, v) of the triangle in `slot`, interpolated from its vertices,
    // and a bound on each coordinate's rounding error (pbrt-v4's, grown by the rounding of
    // 1 - u - v): off the triangle's plane by no more than that.
    Vec3 surface_point(uint32_t slot, Real u, Real v, Vec3& error) const;
    // Unit face normal (v1 - v0) x (v2 - v0) of the triangle in `slot`; zero if it has no area
    // (a sliver kept to close a T-junction, see io/obj_mesh.cpp).
    Vec3 geometric_normal(uint32_t slot) const;
    // Vertex normals interpolated at barycentric (u, v) of the triangle in `slot` and
    // renormalised; the face normal where they cancel out (zero if that has no length either). With `normal_map` (an
    // instance's inverse transpose), each vertex normal is mapped and renormalised first, so that an instance shades as
    // the same mesh built placed would.
    Vec3 shading_normal(uint32_t slot, Real u, Real v) const;
    Vec3 shading_normal(uint32_t slot, Real u, Real v, const Mat3& normal_map) const;
    // The surface coordinates (u, v) at barycentric (u, v) of the triangle in `slot`,
    // interpolated from its corners'; (0, 0) if the mesh was built without them (keep_uvs).
    glm::dvec2 surface_uv(uint32_t slot, Real u, Real v) const;
    // The triangle in `slot` as its file numbers it (after dropping zero-area ones), and its part's tag.
    uint32_t triangle_of(uint32_t slot) const { return hit_records_[slot].triangle; }
    uint32_t tag_of(uint32_t slot) const { return hit_records_[slot].tag; }

    // The box around every triangle.
    const Bounds& bounds() const { return bounds_; }
    size_t triangle_count() const { return triangle_count_; }
    const Bvh& bvh() const { return bvh_; }
    bool brute_force() const { return brute_force_; }
    // True if the BVH is a single leaf holding every triangle (searched without traversal).
    bool one_leaf() const { return one_leaf_; }
    // True if every vertex has the same coordinate on one axis: a ray leaving the mesh's plane
    // never comes back to it (World skips such a mesh for rays that leave it, when it is one
    // object placed as built).
    bool on_axis_plane() const {
        return bounds_.lower.x == bounds_.upper.x || bounds_.lower.y == bounds_.upper.y ||
               bounds_.lower.z == bounds_.upper.z;
    }
    // The BVH's build and the triangles' storage in its order (not placing the vertices).
    double build_seconds() const { return build_seconds_; }
    // Bytes held by the triangles, their hit records and the BVH.
    size_t memory_bytes() const;

private:
    // Calls test_leaf(first, count, range) on the leaves the ray enters, or once on every
    // triangle without a BVH: for the nearest hit (Bvh::closest), or any (kAny, Bvh::any).
    template <bool kAny, typename TestLeaf>
    bool search(const Ray& ray, Interval& range, TraversalCounts& counts, TestLeaf test_leaf) const;
    struct NearestSearch;  // one ray's nearest-hit search, leaf by leaf
    // The four-lane test of the build's rules (kRobust): watertight, or Moller-Trumbore.
    using LaneTester = std::conditional_t<kRobust, TriangleLaneTester, MollerTrumboreLaneTester>;
    // True if a triangle of `run` (at most kTriangleLanes) lies along the tester's ray inside
    // `range`.
    static bool run_blocks(const LaneTester& tester, TriangleRun run, Interval range);
    // The build's steps (the constructor): the BVH and the mesh's box; the triangles and their
    // hit records in the BVH's leaf order.
    void build_tree(const PlacedTriangles& mesh, const std::vector<uint32_t>& first_of_shape,
                    const SearchSettings& settings);
    void store_triangles(PlacedTriangles& mesh, const std::vector<uint32_t>& order, int threads);
    void store_hit_records(const PlacedTriangles& mesh, const std::vector<uint32_t>& order, int threads);

    bool brute_force_;
    // The BVH is one leaf of every triangle (a quad, a box): a search tests them at once, without
    // the box test the world made already (World::may_meet_entry) or a traversal's set-up.
    bool one_leaf_ = false;
    Bvh bvh_;
    // What ties and shading need of a hit, in leaf order too, where the mesh's own arrays
    // would cost a cache miss each for a big mesh.
    struct HitRecord {
        uint32_t triangle;  // the file's triangle number
        uint32_t tag;       // its part's
        uint32_t normals;   // index into vertex_normals_, or kFlat: shaded with its face normal
    };
    static constexpr uint32_t kFlat = ~uint32_t(0);
    // The vertex normals of a hit record's triangle (its face normal three times if flat).
    std::array<Vec3, 3> vertex_normals(uint32_t slot) const;
    TriangleColumns columns() const { return {columns_.data(), triangle_count_ + kTriangleLanes - 1}; }
    // The triangles (entry i is triangle hit_records_[i].triangle) coordinate by coordinate, for
    // testing a leaf's triangles side by side (TriangleColumns).
    LargeArray<Real> columns_;
    size_t triangle_count_ = 0;
    LargeArray<HitRecord> hit_records_;
    LargeArray<std::array<Vec3, 3>> vertex_normals_;  // of the triangles not flat, in leaf order
    LargeArray<std::array<glm::vec2, 3>> uvs_;        // every triangle's, in leaf order (keep_uvs), or none
    Bounds bounds_;
    double build_seconds_ = 0;
};

// The most triangles of a shape built as one primitive of a mesh's BVH (a box's twelve).
constexpr size_t kMostShapeTriangles = 12;
// The first triangle of each small shape, for a mesh whose triangles carry these tags: a run
// of one tag up to kMostShapeTriangles long is a shape, a longer run a shape per triangle; then
// the number of triangles. Empty if that would not at least halve the primitives.
std::vector<uint32_t> small_shapes(const std::vector<uint32_t>& tags);

// Area-weighted vertex normals (zero-area faces add nothing; a vertex with no area gets the
// zero vector, which shading replaces by the face normal).
std::vector<Vec3> area_weighted_normals(std::span<const Vec3> positions,
                                        const std::vector<std::array<uint32_t, 3>>& triangles);

}  // namespace tracer
