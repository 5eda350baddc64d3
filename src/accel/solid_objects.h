// The scene's solids (CSG, scene.h's Solid) as the world keeps them: each solid that is an
// object of its own becomes a program over its leaves, in postfix order (a leaf's span, then the
// operation that combines it with what came before), run along a ray's whole line by
// solid_spans.h's sweep. Its first span end past the ray's start is the hit; the surface there is
// its leaf's, seen from outside the solid (a difference's cut face: the cutter's, turned).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "accel/bvh_search.h"
#include "accel/mesh_accel.h"
#include "accel/round_shapes.h"
#include "accel/solid_meshes.h"
#include "accel/solid_spans.h"
#include "accel/types.h"
#include "scene/scene.h"
#include "scene/triangle_mesh.h"

namespace tracer {

// A box of a solid, placed in the world: rays carried into its own coordinates (p -> to_object
// (p - translate)), its corners there; in the world its upper faces' unit normals (a lower face's
// is the opposite) and its two corners (each on three faces).
struct SolidBox {
    Mat3 to_object{1};
    Vec3 translate{0}, lower{0}, upper{0};
    Vec3 upper_normals[3] = {};
    Vec3 lower_corner{0}, upper_corner{0};
};

// A half-space of a solid: the side `normal` points away from.
struct SolidHalfSpace {
    Vec3 point{0}, normal{0};
};

// A hit on a solid: where, and the face (Hit::primitive: pack_solid_face).
struct SolidHit {
    Real t = 0;
    uint32_t face = 0;
};

// A face of a solid as one number: its leaf, the part of the leaf (a box's face, a cone's side or
// cap) and whether it is seen from the leaf's inside.
inline uint32_t pack_solid_face(const SpanEnd& end) {
    return end.surface << 4 | uint32_t(end.part) << 1 | uint32_t(end.turned);
}

// The surface of a solid at a hit: as a round shape's, its shading normal (a smooth mesh's
// interpolated one; else round.normal) and its material.
struct SolidSurface {
    RoundSurface round;
    Vec3 shading_normal{0};
    int material = 0;
};

class SolidObjects {
public:
    // The scene's solids that are objects of their own (not nested in another), in order; the
    // files of their meshes, and how to search those.
    explicit SolidObjects(const SceneDescription& scene, const SceneMeshes& meshes = {},
                          const SearchSettings& settings = {});

    size_t size() const { return objects_.size(); }
    // The solid's bounds: a difference's are its first part's, an intersection's the overlap of
    // its parts', a union's around all of them. Infinite on an axis a half-space leaves open.
    const Bounds& bounds(uint32_t solid) const { return objects_[solid].bounds; }
    bool bounded(uint32_t solid) const;
    // The nearest crossing of the solid's surface along `ray` with t inside `range`.
    std::optional<SolidHit> nearest(uint32_t solid, const Ray& ray, Interval range) const;
    // The surface where `ray` met `face` at `t`: the point put back on its leaf, with its error
    // bound, and the normal pointing out of the solid.
    SolidSurface surface(const Ray& ray, Real t, uint32_t face) const;
    size_t leaves() const { return kinds_.size(); }

private:
    // A step of a solid's program, over a stack of span lists: Leaf pushes a leaf's span (a
    // solid's first part), Empty an empty list (a solid with no parts), CombineLeaf combines the
    // top list with a leaf's span by `op` (a part after the first), Combine the top two lists.
    struct Step {
        enum class Kind : uint8_t { Leaf, Empty, CombineLeaf, Combine };
        Kind kind = Kind::Leaf;
        SolidOp op = SolidOp::Union;
        uint32_t leaf = 0;  // Leaf, CombineLeaf: index into leaves_
    };
    // A solid of the world. Its leaves are kept relative to `shift` (the middle of its finite
    // parts), and rays carried there: the roundings of a ray's crossings then scale with the
    // ray's distance from the solid, not from the world's origin (a solid at 10^6 in float).
    struct Object {
        uint32_t first_step = 0, steps = 0;
        Bounds bounds;  // in the world
        Vec3 shift{0};
        Real reach = 0;  // the largest coordinate of its leaves' finite corners, relative to shift
    };

    // Each leaf's bounds and reach (the largest coordinate of its finite corners), while built.
    struct LeafExtent {
        Bounds bounds;  // infinite on the axes a half-space does not bound
        Real reach = 0;
    };
    std::vector<LeafExtent> add_leaves(const SceneDescription& scene, const SceneMeshes& meshes);
    // The triangles of each mesh leaf some object uses, placed relative to its object's shift.
    void build_meshes(const SceneDescription& scene, const SceneMeshes& meshes, const SearchSettings& settings);
    void add_program(const SceneDescription& scene, uint32_t solid, const std::vector<Bounds>& solid_bounds,
                     const std::vector<LeafExtent>& extents);
    // Moves the object's leaves (steps from `first_step`) by -shift, and sets its shift and reach.
    void make_relative(Object& object, const std::vector<LeafExtent>& extents);
    SolidPart::Kind kind_of(uint32_t leaf) const { return SolidPart::Kind(kinds_[leaf]); }
    // The leaf's index among those of its kind.
    uint32_t of_kind(uint32_t leaf) const { return leaf - first_leaf_of_kind_[kinds_[leaf]]; }
    // The solid's spans along the ray within `clip` (the part of the line that matters: a span
    // outside it changes nothing inside it), in `out` (the thread's scratch).
    void run(const Object& object, const Ray& ray, Interval clip, Real tolerance, std::vector<SolidSpan>& out) const;
    // Crossings closer than this along `ray` (relative to the object's shift) are one place.
    static Real tolerance(const Object& object, const Ray& ray);
    // True if the leaf's ball shows it lies off the ray's line or wholly outside `clip`.
    bool ball_misses(uint32_t leaf, const Ray& ray, Interval clip) const;
    // The leaf's span, or none if the ray's line misses it or it lies wholly outside `clip`.
    std::optional<SolidSpan> leaf_span(uint32_t leaf, const Ray& ray, Interval clip) const;
    // A mesh leaf's spans (any number) that reach into `clip`, appended to `out`.
    void append_mesh_leaf_spans(uint32_t leaf, const Ray& ray, Interval clip, Real tolerance,
                                std::vector<SolidSpan>& out) const;
    void combine_with_leaf(const Step& step, const Ray& ray, Interval clip, Real tolerance, uint32_t start,
                           std::vector<SolidSpan>& out) const;

    // A sphere around each leaf (a sphere's is itself; infinite for a half-space): a ray tests it
    // first, and most leaves of a solid (a die's pips) are rejected from these few bytes.
    struct LeafBall {
        Vec3 center{0};
        Real radius = kInfinity;
    };
    // The leaves, numbered spheres first, then boxes, cones, half-spaces and meshes (as the scene
    // lists them): for each its kind, material and ball; the shapes of each kind but spheres.
    std::vector<uint8_t> kinds_;
    static constexpr uint32_t kNoObject = ~uint32_t(0);
    std::vector<uint32_t> object_of_leaf_;  // the object whose shift the leaf is relative to, or kNoObject
    std::vector<int> materials_;
    std::vector<LeafBall> balls_;
    std::vector<SolidBox> boxes_;
    std::vector<ConeShape> cones_;
    std::vector<SolidHalfSpace> half_spaces_;
    std::vector<std::unique_ptr<SolidMesh>> meshes_;  // none for a leaf no object uses
    std::vector<uint32_t> first_leaf_of_kind_;        // by SolidPart::Kind: where that kind's leaves start
    std::vector<Step> steps_;
    std::vector<Object> objects_;
};

}  // namespace tracer
