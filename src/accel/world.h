// The renderer's view of a scene and the two ray queries the shading needs: the nearest hit,
// and "is anything in the way". Two levels: one BVH over every bounded object (spheres and
// mesh instances, cones, discs; tinybvh's TLAS) and, below it, each mesh's own BVH (the BLAS), built once
// per mesh file however many mesh blocks place it. Infinite planes are a short list tested
// beside the top level. A search returns a Hit (object, primitive, t, u, v); the surface
// (point, normal, material) is worked out once, after the search, by surface().
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "accel/bvh.h"
#include "accel/mesh_accel.h"
#include "accel/mesh_builds.h"
#include "accel/ray_packet.h"
#include "accel/round_shapes.h"
#include "accel/shadow_frustum.h"
#include "accel/solid_objects.h"
#include "accel/types.h"
#include "scene/placement.h"
#include "scene/scene.h"
#include "scene/triangle_mesh.h"

namespace tracer {

enum class ObjectKind : uint8_t { Sphere, Plane, MeshInstance, Cone, Disc, Solid };

// What a search found.
struct Hit {
    uint32_t object = 0;  // index into World::objects()
    uint32_t primitive =
        0;  // mesh instances: the triangle's slot in its MeshAccel; cones: the ConePart; solids: the face
    Real t = 0;
    Real u = 0, v = 0;  // barycentric coordinates of a triangle hit
};

// No object: a query that skips none (SurfaceHit::convex_object, World::nearest_hit).
constexpr uint32_t kNoObject = ~uint32_t(0);

// The surface at a hit, for shading. Its vectors start unset (World::surface sets each): zeroing
// the record first took 1.7% of Whitted's scene (a `rep stos` of 112 bytes on every hit).
struct SurfaceHit {
    Real t = 0;
    Vec3 point;             // on the surface
    Vec3 normal;            // shading normal, unit length, not yet turned towards the ray
    int material = 0;       // index into World::materials()
    Vec3 error;             // a bound on each coordinate's rounding error in `point`
    Vec3 geometric_normal;  // the surface's own unit normal (for spawning rays off it)
    // The object hit, if a ray leaving it along its geometric normal's side cannot meet it
    // again: a sphere or cone (the outward side of a convex solid), a disc or a mesh on an axis
    // plane (either side); kNoObject for planes (tested beside the top level), other meshes and
    // solids (CSG).
    uint32_t convex_object = kNoObject;
    bool flat = false;  // convex_object is flat: rays leave it for good on either side
};

// The object that a ray spawned off `hit` in `direction` cannot meet again, for a query to
// skip it, or kNoObject. The naive rule (TRACER_ROBUST=OFF) skips nothing: its self-hits are
// what it shows.
inline uint32_t object_left_behind(const SurfaceHit& hit, const Vec3& direction) {
    if constexpr (!kRobust) return kNoObject;
    return hit.flat || glm::dot(hit.geometric_normal, direction) > 0 ? hit.convex_object : kNoObject;
}

// The shape that blocked a shadow ray (World::occluded): an entry of the top level and, in a
// mesh, the run of triangles tested together that held the blocker.
struct Occluder {
    static constexpr uint32_t kNone = ~uint32_t(0);
    uint32_t entry = kNone;
    TriangleRun triangles;
};

// Work done by searches, for --stats: the top level's box tests and object tests, and the
// box and triangle tests inside meshes.
struct SearchCounts {
    TraversalCounts objects;
    TraversalCounts triangles;
    SearchCounts& operator+=(const SearchCounts& other) {
        objects += other.objects;
        triangles += other.triangles;
        return *this;
    }
};

// One shape of the scene: its kind, its index among the shapes of that kind, its material.
struct Object {
    ObjectKind kind;
    uint32_t index;  // a sphere: its entry in the top level; into planes, instances, cones or discs
    int material;
};

// A mesh block, or all the flat shapes (World::instances() holds the scene's mesh blocks in
// order, then one shared by its triangles, quads and boxes): a mesh and where it is placed. Flat shapes and the
// blocks whose file no other block uses are built placed in the world, all of them merged into
// one mesh (`placed`: rays reach it unchanged); a file that several blocks name is built once in
// its own coordinates, and rays are carried there by each block's `to_object`.
struct MeshInstance {
    uint32_t mesh = 0;  // index into World::meshes()
    bool placed = true;
    Mat3 to_world{1};   // the placement's linear part
    Mat3 to_object{1};  // its inverse
    Vec3 translate{0};

    // The ray in the mesh's coordinates (of a mesh not built placed), with the same t along it.
    Ray to_mesh(const Ray& ray) const { return {to_object * (ray.origin - translate), to_object * ray.direction}; }
};

// Up to this many bounded objects are tested one after the other instead of through the top
// level's BVH (measured: docs/bench/many-objects.md).
constexpr size_t kLinearObjects = 8;

class World {
public:
    // The shapes of a validated scene with its mesh files as loaded (SceneMeshes), behind the
    // scene's accelerator, built on `threads` threads (0: all). `flatten_shared` merges every
    // mesh block into one placed mesh, shared files too (for measuring instancing against it).
    World(const SceneDescription& scene, const SceneMeshes& meshes = {}, int threads = 0, bool flatten_shared = false);
    // The same, emptying the scene's lists of flat shapes (triangles, quads, boxes) once they
    // are placed, before their BVH is built: a million of them need that memory for the build.
    struct ReleaseFlatShapes {};
    World(SceneDescription& scene, const SceneMeshes& meshes, int threads, ReleaseFlatShapes);
    // The same for a frame of an animation: every mesh file is built in its own coordinates
    // through `reuse` (once for all the frames), each block placed as an instance of it.
    World(SceneDescription& scene, const SceneMeshes& meshes, int threads, ReleaseFlatShapes, MeshBuildCache& reuse);

    // The nearest surface along `ray` with t inside `range`, not counting object `left_behind`
    // (object_left_behind: the convex shape the ray leaves, which it cannot meet again).
    std::optional<Hit> nearest_hit(const Ray& ray, Interval range, SearchCounts& counts,
                                   uint32_t left_behind = kNoObject) const;
    // nearest_hit for each of *rays[0 .. count) (at most kPacket) with t inside `range`, skipping
    // no object: the same answers. Where the objects are few enough to be tested one by one,
    // each mesh is searched for all the rays that may meet it together (intersect_packet).
    void nearest_hits(const Ray* const* rays, int count, Interval range, std::optional<Hit>* out,
                      SearchCounts& counts) const;
    // Where packets pay, decided in two steps. First the frame: true if a render of `pixels`
    // should trace its primary rays in tiles (trace_packet): the objects are tested one by one,
    // some are meshes, and no mesh has more than one triangle for every kPixelsPerTriangle
    // pixels (where a tile's rays meet leaves of a pixel or less, each meets them in the
    // packet's order, not its own nearest first, and tiles are slower: docs/bench/code-figures.md).
    bool frame_takes_tiles(size_t pixels) const {
        return packet_search_possible_ && pixels >= kPixelsPerTriangle * largest_mesh_triangles_;
    }
    static constexpr size_t kPixelsPerTriangle = 4;
    // Then each packet: true if nearest_hits does better than nearest_hit on *rays[0 .. count),
    // that is if at least two of them may meet one mesh (else each is searched alone).
    bool packet_shares_a_mesh(const Ray* const* rays, int count) const;
    // The surface at a hit that nearest_hit returned for `ray`.
    SurfaceHit surface(const Ray& ray, const Hit& hit) const;
    // True if any surface lies along `ray` with t inside `range` (for shadow rays).
    bool occluded(const Ray& ray, Interval range, SearchCounts& counts) const {
        Occluder none;
        return occluded(ray, range, counts, none);
    }
    // occluded, testing `last` first: the shape that blocked an earlier shadow ray towards the
    // same light, which mostly blocks its neighbours too (Haines & Greenberg's shadow cache).
    // The answer is the same either way; `last` becomes the shape that blocked this ray, if any.
    // Object `left_behind` is not tested (as for nearest_hit).
    bool occluded(const Ray& ray, Interval range, SearchCounts& counts, Occluder& last,
                  uint32_t left_behind = kNoObject) const;
    // What may block some shadow ray of `frustum`: the top level's entries whose boxes meet it
    // (among those of `within`, a frustum holding this one, if given), the planes it crosses
    // and any unbounded solid; `everything` if they are more than ShadowCandidates holds.
    void shadow_candidates(const ShadowFrustum& frustum, const ShadowCandidates* within, ShadowCandidates& out) const;
    // occluded for a ray of a frustum whose candidates these are: the same answer, only they tested.
    bool occluded_among(const ShadowCandidates& candidates, const Ray& ray, Interval range, SearchCounts& counts,
                        Occluder& last, uint32_t left_behind) const;
    // The shape that `blocker` names, if it is convex (a sphere, a closed cone, a disc): a shadow
    // frustum whose four edge rays one convex shape blocks is blocked all through. (A mesh's
    // triangles are convex too, but naming the one of a run that blocks cost as much as it saved,
    // measured on scenes/lights/window.scn.)
    struct ConvexBlocker {
        static constexpr uint32_t kNone = kNoObject;
        uint32_t object = kNone;  // kNone if not convex
        int material = -1;
    };
    ConvexBlocker convex_blocker(const Occluder& blocker) const;
    // The object of a candidate's entry (ShadowCandidates::entries), as object_left_behind names it.
    uint32_t candidate_object(uint32_t entry) const { return bounded_[entry].object; }
    // A number no other World of this process has (for caches kept between rays).
    uint64_t serial() const { return serial_; }
    // False only if the ray's line misses a bounding sphere of every bounded object, and there
    // are no planes.
    bool may_hit(const Ray& ray) const;

    const std::vector<Material>& materials() const { return materials_; }
    const std::vector<Pattern>& patterns() const { return patterns_; }
    // True if material `index`'s patterns read the surface's (u, v) (else surface_uv is not needed).
    bool maps_by_uv(int index) const { return !uv_materials_.empty() && uv_materials_[size_t(index)]; }
    // True if material `index`'s ka pattern is its kd pattern times a colour (same_but_multiply).
    bool ka_scales_kd(int index) const { return !ka_scales_kd_.empty() && ka_scales_kd_[size_t(index)]; }
    const std::vector<ImageFile>& images() const { return images_; }
    // The surface coordinates (u, v) of a hit (scene/pattern.h's uv mapping; docs/guide/patterns.md):
    // a triangle's from its corners', a round shape's or a plane's from where the hit lies in the
    // shape's own coordinates, `to_object` being the linear part of the map there from the world.
    // (0, 0) on meshes built without them (no pattern maps by them).
    glm::dvec2 surface_uv(const Hit& hit, const SurfaceHit& surface, const glm::dmat3& to_object) const;
    // True if some material transmits (kt > 0): only then can the ray tree branch.
    bool refracts() const { return refracts_; }
    const std::vector<Light>& lights() const { return lights_; }
    const std::vector<Object>& objects() const { return objects_; }
    const MeshList& meshes() const { return meshes_; }
    const std::vector<MeshInstance>& instances() const { return instances_; }
    const SolidObjects& solids() const { return solids_; }
    // The mesh that holds the shapes built placed (flat shapes, unshared mesh blocks), if any.
    std::optional<uint32_t> merged_mesh() const { return merged_mesh_; }
    // The top level: a BVH over the bounded objects, unless they are few (kLinearObjects) or
    // the scene asks for no accelerator.
    bool top_level_linear() const { return linear_; }
    const Bvh& top_level() const { return top_; }
    double top_level_build_seconds() const { return top_build_seconds_; }
    size_t bounded_objects() const { return bounded_.size() - extra_entries_; }
    // The top level's entries: one per bounded object, and the pieces of long cones beyond their first.
    size_t top_level_entries() const { return bounded_.size(); }
    // Bytes held by the top level (its BVH, the objects, the instances; not the meshes).
    size_t top_level_memory_bytes() const;

private:
    struct PlaneShape {
        Vec3 point;
        Vec3 normal;
        uint32_t object;  // index into objects_
    };
    struct UnboundedSolid {  // a solid a half-space leaves open on some axis
        uint32_t index;      // into solids_
        uint32_t object;
    };
    // Bounded::object of the merged mesh: each triangle's object is its hit record's tag. Not
    // kNoObject: a search skips the entry whose object is the one its ray left behind.
    static constexpr uint32_t kObjectOfTriangle = kNoObject - 1;
    // An entry of the top level, in its BVH's leaf order.
    struct Bounded {
        Vec3 center;  // sphere: the sphere; others: a sphere around their box
        Real radius;
        uint32_t object;  // index into objects_, or kObjectOfTriangle
        uint32_t index;  // into instances_, cones_, discs_ or solids_ (a sphere's is not read: the entry is the sphere)
        ObjectKind kind;
    };

    // The cone a search tested last: a long cone's pieces (cone_piece_boxes) cost one test.
    struct LastCone {
        uint32_t index = ~uint32_t(0);
        // False if `b` is a piece of the cone just tested (its answer to the search is known);
        // true for any other entry, which a cone then becomes the last of.
        bool untested(const Bounded& b) {
            if (b.kind != ObjectKind::Cone) return true;
            if (b.index == index) return false;
            index = b.index;
            return true;
        }
    };

    World(const SceneDescription& scene, const SceneMeshes& meshes, int threads, bool flatten_shared,
          SceneDescription* releasable, MeshBuildCache* reuse);
    // `releasable`: the scene (the same object) whose flat shapes are emptied once placed, or null;
    // `reuse`: where mesh files are built (each block an instance), or null.
    void add_meshes(const SceneDescription& scene, const SceneMeshes& meshes, const SearchSettings& settings,
                    bool flatten_shared, SceneDescription* releasable, MeshBuildCache* reuse);
    void add_bounded(const Bounds& box, uint32_t object, uint32_t index, ObjectKind kind = ObjectKind::MeshInstance);
    void add_round_shapes(const SceneDescription& scene, const SearchSettings& settings);
    bool hit_bounded(const Bounded& b, const Ray& ray, Interval& range, Hit& hit, SearchCounts& counts) const;
    bool bounded_blocks(uint32_t entry, const Ray& ray, Interval range, SearchCounts& counts, Occluder& blocker) const;
    void build_top_level(const SearchSettings& settings);
    bool hit_instance(uint32_t index, uint32_t object, const Ray& ray, Interval& range, Hit& hit,
                      SearchCounts& counts) const;
    bool instance_blocks(uint32_t entry, const Ray& ray, Interval range, SearchCounts& counts, Occluder& blocker) const;
    // shadow_candidates' step for out's next entry (`entry`): the leaves of its mesh that meet
    // the frustum, from `within`'s entry `within_index` if given, or kWholeMesh.
    void add_mesh_leaves(const ShadowFrustum& frustum, uint32_t entry, const ShadowCandidates* within, int within_index,
                         ShadowCandidates& out) const;
    bool occluder_blocks(const Occluder& occluder, const Ray& ray, Interval range, SearchCounts& counts,
                         uint32_t left_behind) const;
    // The nearest of the planes and the unbounded solids (tested beside the top level).
    bool nearest_plane(const Ray& ray, Interval& range, Hit& hit) const;
    void add_solids();
    // surface's steps for a sphere and a mesh instance (out.t and out.material already set).
    void sphere_surface(const Ray& ray, const Hit& hit, SurfaceHit& out) const;
    void mesh_surface(const Ray& ray, const Hit& hit, SurfaceHit& out) const;
    // The first steps of nearest_one_by_one: the spheres (bounded_'s first entries while the
    // top level is linear), then the planes.
    bool nearest_sphere_or_plane(const Ray& ray, Interval& range, Hit& hit, uint32_t left_behind) const;
    bool nearest_one_by_one(const Ray& ray, Interval& range, Hit& hit, SearchCounts& counts,
                            uint32_t left_behind) const;
    // False only if the ray misses bounded object `entry` before range.max, while the top level
    // is linear: the line misses the sphere around its box, or the ray misses the box.
    bool may_meet_entry(size_t entry, const Ray& ray, Interval range) const;

    std::vector<Object> objects_;
    std::vector<PlaneShape> planes_;
    MeshList meshes_;
    std::vector<MeshInstance> instances_;
    std::optional<uint32_t> merged_mesh_;  // the mesh of the shapes built placed, if any
    std::vector<ConeShape> cones_;
    std::vector<DiscShape> discs_;
    SolidObjects solids_;
    std::vector<UnboundedSolid> unbounded_solids_;
    std::vector<Bounded> bounded_;
    size_t extra_entries_ = 0;          // the pieces of long cones beyond the first (cone_piece_boxes)
    uint32_t sphere_count_ = 0;         // the spheres: bounded_'s first entries while the top level is linear
    LargeArray<Bounds> boxes_;          // of bounded_, while the world is built
    std::vector<Bounds> linear_boxes_;  // of bounded_ (padded_for_rays) while the top level is linear
    Bvh top_;
    bool linear_ = true;
    bool packet_search_possible_ = false;  // linear_, and some object is a mesh
    size_t largest_mesh_triangles_ = 0;    // of the meshes instanced
    double top_build_seconds_ = 0;
    Vec3 sphere_center_{0};  // around every bounded object, for may_hit
    Real sphere_radius2_ = -1;
    bool refracts_ = false;
    std::vector<Material> materials_;
    std::vector<Light> lights_;
    std::vector<Pattern> patterns_;
    std::vector<ImageFile> images_;
    std::vector<uint8_t> uv_materials_;  // per material: maps_by_uv (empty if none does)
    std::vector<uint8_t> ka_scales_kd_;  // per material: ka_scales_kd (empty if no material has patterns)
    std::vector<Cone> cone_ends_;        // the cones as the scene gives them, when surface coordinates are kept
    uint64_t serial_;
};

}  // namespace tracer

#include "accel/world_queries.inl"  // the queries' inline definitions
