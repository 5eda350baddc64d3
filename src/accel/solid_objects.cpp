#include "accel/solid_objects.h"

#include <algorithm>
#include <cmath>
#include <span>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "accel/shape_bounds.h"
#include "accel/solid_leaves.h"
#include "scene/mesh_facts.h"
#include "scene/placement.h"

namespace tracer {
namespace {

// The largest coordinate of a finite box's corners.
Real reach_of(const Bounds& box) {
    Real reach = 0;
    for (const Vec3& corner : {box.lower, box.upper})
        for (int axis = 0; axis < 3; ++axis)
            if (std::isfinite(corner[axis])) reach = std::max(reach, std::abs(corner[axis]));
    return reach;
}

SolidBox box_leaf(const Box& box, Bounds& bounds) {
    SolidBox leaf;
    const Placement placement(box);
    const glm::dmat3 to_object = glm::inverse(placement.linear);
    leaf.to_object = Mat3(to_object);
    leaf.translate = Vec3(placement.translate);
    leaf.lower = Vec3(box.min);
    leaf.upper = Vec3(box.max);
    // A face's normal maps by the inverse transpose: the upper face across axis i, e_i, to row i.
    for (int axis = 0; axis < 3; ++axis)
        leaf.upper_normals[axis] =
            Vec3(glm::normalize(glm::dvec3(to_object[0][axis], to_object[1][axis], to_object[2][axis])));
    leaf.lower_corner = Vec3(placement.point(box.min));
    leaf.upper_corner = Vec3(placement.point(box.max));
    bounds = placed_box({leaf.lower, leaf.upper}, placement);
    return leaf;
}

Bounds cone_bounds(const Cone& cone) {
    const glm::dvec3 axis = glm::normalize(cone.top - cone.base);
    Bounds bounds = disc_box(cone.base, axis, cone.base_radius);
    bounds.extend(disc_box(cone.top, axis, cone.top_radius));
    return bounds;
}

// A half-space is infinite, but bounded on an axis it lies across.
Bounds half_space_bounds(const Plane& plane) {
    Bounds bounds{Vec3(-kInfinity), Vec3(kInfinity)};
    for (int axis = 0; axis < 3; ++axis) {
        if (std::abs(plane.normal[axis]) != 1) continue;
        if (plane.normal[axis] > 0)
            bounds.upper[axis] = Real(plane.point[axis]);
        else
            bounds.lower[axis] = Real(plane.point[axis]);
    }
    return bounds;
}

Bounds overlap(const Bounds& a, const Bounds& b) {
    return {glm::max(a.lower, b.lower), glm::min(a.upper, b.upper)};
}

bool is_empty(const Bounds& box) {
    return !(box.lower.x <= box.upper.x && box.lower.y <= box.upper.y && box.lower.z <= box.upper.z);
}

// The scratch of the spans' sweep, one per thread: a ray allocates nothing once it has run.
struct SpanScratch {
    std::vector<SolidSpan> spans, combined, mesh_spans;
    std::vector<uint32_t> starts;
};
thread_local SpanScratch scratch;

// The list `out` from `start` to `end` replaced by itself `op` `b` (which may lie in `out` past `end`).
void replace_by_combination(SolidOp op, std::vector<SolidSpan>& out, size_t start, size_t end,
                            std::span<const SolidSpan> b, Real tolerance) {
    std::vector<SolidSpan>& combined = scratch.combined;
    combined.clear();
    combine_spans(op, std::span(out.data() + start, end - start), b, tolerance, combined);
    out.resize(start);
    out.insert(out.end(), combined.begin(), combined.end());
}

}  // namespace

SolidObjects::SolidObjects(const SceneDescription& scene, const SceneMeshes& meshes, const SearchSettings& settings) {
    const std::vector<LeafExtent> extents = add_leaves(scene, meshes);
    object_of_leaf_.assign(kinds_.size(), kNoObject);
    // Each solid's bounds, from its parts' (a nested solid comes after the solid it is part of).
    std::vector<Bounds> solid_bounds(scene.solids.size());
    for (size_t i = scene.solids.size(); i-- > 0;) {
        const Solid& solid = scene.solids[i];
        Bounds box;
        bool first = true;
        for (const SolidPart& part : solid.parts) {
            const Bounds& of_part = part.kind == SolidPart::Kind::Solid
                                        ? solid_bounds[part.index]
                                        : extents[first_leaf_of_kind_[size_t(part.kind)] + part.index].bounds;
            if (first)
                box = of_part;
            else if (solid.op == SolidOp::Union)
                box.extend(of_part);
            else if (solid.op == SolidOp::Intersection)
                box = overlap(box, of_part);
            first = false;
        }
        solid_bounds[i] = box;
    }
    for (uint32_t i = 0; i < scene.solids.size(); ++i)
        if (!scene.solids[i].nested) add_program(scene, i, solid_bounds, extents);
    build_meshes(scene, meshes, settings);
}

void SolidObjects::build_meshes(const SceneDescription& scene, const SceneMeshes& meshes,
                                const SearchSettings& settings) {
    meshes_.resize(scene.solid_meshes.size());
    for (uint32_t i = 0; i < scene.solid_meshes.size(); ++i) {
        const uint32_t leaf = first_leaf_of_kind_[size_t(SolidPart::Kind::Mesh)] + i;
        if (object_of_leaf_[leaf] == kNoObject || i >= meshes.file_of_solid_mesh.size()) continue;
        const Mesh& mesh = scene.solid_meshes[i];
        MeshPart part{meshes.files[meshes.file_of_solid_mesh[i]].get(), Placement(mesh), 0, mesh.flat};
        part.placement.translate -= glm::dvec3(objects_[object_of_leaf_[leaf]].shift);
        meshes_[i] = std::make_unique<SolidMesh>(SolidMesh{MeshAccel({part}, settings), mesh.flat});
    }
}

std::vector<SolidObjects::LeafExtent> SolidObjects::add_leaves(const SceneDescription& scene,
                                                               const SceneMeshes& meshes) {
    std::vector<LeafExtent> extents;
    first_leaf_of_kind_.assign(size_t(SolidPart::Kind::Solid) + 1, 0);
    auto add = [&](SolidPart::Kind kind, int material, const Bounds& bounds) {
        kinds_.push_back(uint8_t(kind));
        materials_.push_back(material);
        extents.push_back({bounds, reach_of(bounds)});
        LeafBall& ball = balls_.emplace_back();
        if (kind != SolidPart::Kind::HalfSpace) {  // around its box, a little larger than its rounding
            ball.center = bounds.center();
            ball.radius = glm::length(bounds.upper - bounds.lower) * Real(0.5 + 1e-6);
        }
        return &ball;
    };
    first_leaf_of_kind_[size_t(SolidPart::Kind::Sphere)] = uint32_t(kinds_.size());
    for (const Sphere& sphere : scene.solid_spheres) {
        const Vec3 center(sphere.center);
        const Real radius(sphere.radius);
        *add(SolidPart::Kind::Sphere, sphere.material, {center - radius, center + radius}) = {center, radius};
    }
    first_leaf_of_kind_[size_t(SolidPart::Kind::Box)] = uint32_t(kinds_.size());
    for (const Box& box : scene.solid_boxes) {
        Bounds bounds;
        boxes_.push_back(box_leaf(box, bounds));
        add(SolidPart::Kind::Box, box.material, bounds);
    }
    first_leaf_of_kind_[size_t(SolidPart::Kind::Cone)] = uint32_t(kinds_.size());
    for (const Cone& cone : scene.solid_cones) {
        cones_.push_back(make_cone_shape(cone.base, cone.top, cone.base_radius, cone.top_radius, true));
        add(SolidPart::Kind::Cone, cone.material, cone_bounds(cone));
    }
    first_leaf_of_kind_[size_t(SolidPart::Kind::HalfSpace)] = uint32_t(kinds_.size());
    for (const Plane& plane : scene.half_spaces) {
        half_spaces_.push_back({Vec3(plane.point), Vec3(plane.normal)});
        add(SolidPart::Kind::HalfSpace, plane.material, half_space_bounds(plane));
        extents.back().reach = std::max({std::abs(plane.point.x), std::abs(plane.point.y), std::abs(plane.point.z)});
    }
    first_leaf_of_kind_[size_t(SolidPart::Kind::Mesh)] = uint32_t(kinds_.size());
    for (size_t i = 0; i < scene.solid_meshes.size(); ++i) {
        const Mesh& mesh = scene.solid_meshes[i];
        // Without its file (a caller that read none: the fuzz targets), a mesh is empty.
        const TriangleMesh none;
        const bool read = i < meshes.file_of_solid_mesh.size();
        const MeshFacts facts = mesh_facts(read ? *meshes.files[meshes.file_of_solid_mesh[i]] : none, mesh);
        add(SolidPart::Kind::Mesh, mesh.material, {Vec3(facts.lower), Vec3(facts.upper)});
    }
    return extents;
}

// The solid's program, walked depth first without recursion (solids may nest 10^4 deep): each
// leaf, and after each part but a solid's first, the solid's operation.
void SolidObjects::add_program(const SceneDescription& scene, uint32_t root, const std::vector<Bounds>& solid_bounds,
                               const std::vector<LeafExtent>& extents) {
    if (is_empty(solid_bounds[root])) return;  // an intersection of parts apart: nothing
    Object object;
    object.first_step = uint32_t(steps_.size());
    object.bounds = solid_bounds[root];
    struct Frame {
        uint32_t solid;
        size_t next;  // the part to emit next
    };
    std::vector<Frame> stack{{root, 0}};
    while (!stack.empty()) {
        const Frame frame = stack.back();
        const Solid& solid = scene.solids[frame.solid];
        if (frame.next == solid.parts.size()) {
            if (solid.parts.empty()) steps_.push_back({Step::Kind::Empty, SolidOp::Union, 0});
            stack.pop_back();
            if (!stack.empty() && stack.back().next >= 2)
                steps_.push_back({Step::Kind::Combine, scene.solids[stack.back().solid].op, 0});
            continue;
        }
        const SolidPart part = solid.parts[frame.next];
        ++stack.back().next;
        if (part.kind == SolidPart::Kind::Solid) {
            stack.push_back({part.index, 0});
            continue;
        }
        const uint32_t leaf = first_leaf_of_kind_[size_t(part.kind)] + part.index;
        steps_.push_back({frame.next == 0 ? Step::Kind::Leaf : Step::Kind::CombineLeaf, solid.op, leaf});
    }
    object.steps = uint32_t(steps_.size()) - object.first_step;
    make_relative(object, extents);
    objects_.push_back(object);
}

void SolidObjects::make_relative(Object& object, const std::vector<LeafExtent>& extents) {
    // Step 1: the middle of the leaves' finite extents (a half-space's: its point).
    Bounds finite;
    for (uint32_t i = object.first_step; i < object.first_step + object.steps; ++i) {
        if (steps_[i].kind == Step::Kind::Empty || steps_[i].kind == Step::Kind::Combine) continue;
        const uint32_t leaf = steps_[i].leaf;
        if (kind_of(leaf) == SolidPart::Kind::HalfSpace)
            finite.extend(half_spaces_[of_kind(leaf)].point);
        else
            finite.extend(extents[leaf].bounds);
    }
    const Vec3 shift = finite.lower.x <= finite.upper.x ? finite.center() : Vec3(0);
    object.shift = shift;
    // Step 2: each leaf moved, and its reach from there.
    for (uint32_t i = object.first_step; i < object.first_step + object.steps; ++i) {
        if (steps_[i].kind == Step::Kind::Empty || steps_[i].kind == Step::Kind::Combine) continue;
        const uint32_t leaf = steps_[i].leaf;
        object_of_leaf_[leaf] = uint32_t(objects_.size());
        balls_[leaf].center -= shift;
        switch (kind_of(leaf)) {
            case SolidPart::Kind::Box: {
                SolidBox& box = boxes_[of_kind(leaf)];
                box.translate -= shift, box.lower_corner -= shift, box.upper_corner -= shift;
                break;
            }
            case SolidPart::Kind::Cone: cones_[of_kind(leaf)].tip -= shift; break;
            case SolidPart::Kind::HalfSpace: half_spaces_[of_kind(leaf)].point -= shift; break;
            case SolidPart::Kind::Sphere:
            case SolidPart::Kind::Mesh:  // built relative to the shift (build_meshes)
            case SolidPart::Kind::Solid: break;
        }
        const Bounds& box = extents[leaf].bounds;
        object.reach = std::max(object.reach,
                                kind_of(leaf) == SolidPart::Kind::HalfSpace
                                    ? reach_of({half_spaces_[of_kind(leaf)].point, half_spaces_[of_kind(leaf)].point})
                                    : reach_of({box.lower - shift, box.upper - shift}));
    }
}

bool SolidObjects::bounded(uint32_t solid) const {
    const Bounds& box = objects_[solid].bounds;
    for (int axis = 0; axis < 3; ++axis)
        if (!std::isfinite(box.lower[axis]) || !std::isfinite(box.upper[axis])) return false;
    return true;
}

[[gnu::always_inline]] inline bool SolidObjects::ball_misses(uint32_t leaf, const Ray& ray, Interval clip) const {
    // Along the ray, the leaf lies within its ball's radius of the ball centre's foot: nothing
    // to find outside the clip (a pip behind a ray leaving the die), nor if the line passes
    // outside the ball (most pips).
    const LeafBall& ball = balls_[leaf];
    if (ball.radius < kInfinity) {
        const Vec3 to_center = ball.center - ray.origin;
        const Real foot = dot(to_center, ray.direction);
        if (foot + ball.radius < clip.min || foot - ball.radius > clip.max) return true;
        const Vec3 across = glm::cross(to_center, ray.direction);
        if (dot(across, across) > ball.radius * ball.radius * Real(1 + 1e-6)) return true;
    }
    return false;
}

[[gnu::always_inline]] inline std::optional<SolidSpan> SolidObjects::leaf_span(uint32_t index, const Ray& ray,
                                                                               Interval clip) const {
    if (ball_misses(index, ray, clip)) return std::nullopt;
    const LeafBall& ball = balls_[index];
    std::optional<SolidSpan> span;
    switch (kind_of(index)) {
        case SolidPart::Kind::Sphere: span = sphere_span(ray, ball.center, ball.radius, index); break;
        case SolidPart::Kind::Box: {
            const SolidBox& box = boxes_[of_kind(index)];
            const Ray own{box.to_object * (ray.origin - box.translate), box.to_object * ray.direction};
            span = box_span(own, box.lower, box.upper, index);
            break;
        }
        case SolidPart::Kind::Cone: span = cone_span(ray, cones_[of_kind(index)], index); break;
        case SolidPart::Kind::HalfSpace: {
            const SolidHalfSpace& half = half_spaces_[of_kind(index)];
            span = half_space_span(ray, half.point, half.normal, index);
            break;
        }
        case SolidPart::Kind::Mesh:  // append_mesh_leaf_spans
        case SolidPart::Kind::Solid: break;
    }
    if (span && (span->leave.t < clip.min || span->enter.t > clip.max)) return std::nullopt;
    return span;
}

void SolidObjects::append_mesh_leaf_spans(uint32_t leaf, const Ray& ray, Interval clip, Real tolerance,
                                          std::vector<SolidSpan>& out) const {
    if (ball_misses(leaf, ray, clip) || !meshes_[of_kind(leaf)]) return;
    const size_t first = out.size();
    append_mesh_spans(meshes_[of_kind(leaf)]->accel, ray, clip.max, tolerance, leaf, out);
    // Those wholly before the clip change nothing in it.
    size_t kept = first;
    while (kept < out.size() && out[kept].leave.t < clip.min) ++kept;
    out.erase(out.begin() + std::ptrdiff_t(first), out.begin() + std::ptrdiff_t(kept));
}

// CombineLeaf: the list from `start` to the end, op the leaf's span, in place.
[[gnu::always_inline]] inline void SolidObjects::combine_with_leaf(const Step& step, const Ray& ray, Interval clip,
                                                                   Real tolerance, uint32_t start,
                                                                   std::vector<SolidSpan>& out) const {
    const bool a_empty = start == out.size();
    if (a_empty && step.op != SolidOp::Union) return;  // nothing to cut from or to overlap
    // Only where the list lies can a leaf cut or overlap it.
    if (step.op != SolidOp::Union)
        clip = {std::max(clip.min, out[start].enter.t - tolerance), std::min(clip.max, out.back().leave.t + tolerance)};
    if (kind_of(step.leaf) == SolidPart::Kind::Mesh) {
        std::vector<SolidSpan>& spans = scratch.mesh_spans;
        spans.clear();
        append_mesh_leaf_spans(step.leaf, ray, clip, tolerance, spans);
        if (spans.empty()) {
            if (step.op == SolidOp::Intersection) out.resize(start);
        } else if (a_empty) {
            out.insert(out.end(), spans.begin(), spans.end());
        } else {
            replace_by_combination(step.op, out, start, out.size(), spans, tolerance);
        }
        return;
    }
    const std::optional<SolidSpan> b = leaf_span(step.leaf, ray, clip);
    if (!b) {
        if (step.op == SolidOp::Intersection) out.resize(start);
        return;
    }
    if (a_empty) return out.push_back(*b);
    replace_by_combination(step.op, out, start, out.size(), std::span(&*b, 1), tolerance);
}

void SolidObjects::run(const Object& object, const Ray& ray, Interval clip, Real tolerance,
                       std::vector<SolidSpan>& out) const {
    std::vector<uint32_t>& starts = scratch.starts;
    out.clear();
    starts.clear();
    for (uint32_t i = object.first_step; i < object.first_step + object.steps; ++i) {
        const Step& step = steps_[i];
        switch (step.kind) {
            case Step::Kind::Leaf:
                starts.push_back(uint32_t(out.size()));
                if (kind_of(step.leaf) == SolidPart::Kind::Mesh)
                    append_mesh_leaf_spans(step.leaf, ray, clip, tolerance, out);
                else if (auto span = leaf_span(step.leaf, ray, clip))
                    out.push_back(*span);
                break;
            case Step::Kind::Empty: starts.push_back(uint32_t(out.size())); break;
            case Step::Kind::CombineLeaf: combine_with_leaf(step, ray, clip, tolerance, starts.back(), out); break;
            case Step::Kind::Combine: {
                const uint32_t b = starts.back();
                starts.pop_back();
                const uint32_t a = starts.back();
                const bool a_empty = a == b, b_empty = b == out.size();
                // Nothing to cut from or to overlap; or nothing to add, cut or overlap with.
                if (a_empty && step.op != SolidOp::Union) {
                    out.resize(a);
                    break;
                }
                if (b_empty) {
                    if (step.op == SolidOp::Intersection) out.resize(a);
                    break;
                }
                replace_by_combination(step.op, out, a, b, std::span(out.data() + b, out.size() - b), tolerance);
                break;
            }
        }
    }
}

Real SolidObjects::tolerance(const Object& object, const Ray& ray) {
    const Vec3 o = abs_each(ray.origin);
    return gamma(32) * (std::max({o.x, o.y, o.z}) + object.reach);
}

std::optional<SolidHit> SolidObjects::nearest(uint32_t solid, const Ray& world_ray, Interval range) const {
    const Object& object = objects_[solid];
    const Ray ray{world_ray.origin - object.shift, world_ray.direction};
    // Crossings closer than this are one place; one this close to the origin is the surface a
    // spawned ray leaves (its t computed from the moved origin may round either way).
    const Real tolerance = SolidObjects::tolerance(object, ray);
    std::vector<SolidSpan>& spans = scratch.spans;
    const Real from = std::max(range.min, tolerance);
    run(object, ray, {from - tolerance, range.max + tolerance}, tolerance, spans);
    for (const SolidSpan& span : spans)
        for (const SpanEnd& end : {span.enter, span.leave}) {
            if (!(end.t < range.max)) return std::nullopt;
            if (end.t > from) return SolidHit{end.t, pack_solid_face(end)};
        }
    return std::nullopt;
}

SolidSurface SolidObjects::surface(const Ray& world_ray, Real t, uint32_t face) const {
    const uint32_t leaf = face >> 4, part = (face >> 1) & 7;
    const Object& object = objects_[object_of_leaf_[leaf]];
    const Vec3& shift = object.shift;
    const Ray ray{world_ray.origin - shift, world_ray.direction};
    SolidSurface out;
    out.material = materials_[leaf];
    RoundSurface& round = out.round;
    // A point put back on a flat face: projected onto its plane.
    auto on_plane = [&](const Vec3& point, const Vec3& normal) {
        const Vec3 along_ray = ray.at(t);
        round.point = along_ray - glm::dot(along_ray - point, normal) * normal;
        round.error = gamma(8) * (abs_each(round.point) + abs_each(point));
        round.normal = normal;
    };
    switch (kind_of(leaf)) {
        case SolidPart::Kind::Sphere: {
            const LeafBall& sphere = balls_[leaf];
            const Vec3 from_center = ray.at(t) - sphere.center;
            const Real length = glm::length(from_center);
            round.normal = length > 0 ? from_center * (1 / length) : Vec3(0, 0, 1);
            const Vec3 on_sphere = round.normal * sphere.radius;
            round.point = sphere.center + on_sphere;
            round.error = gamma(6) * (abs_each(sphere.center) + abs_each(on_sphere));
            break;
        }
        case SolidPart::Kind::Cone: round = cone_surface(ray, cones_[of_kind(leaf)], t, part); break;
        case SolidPart::Kind::Box: {
            const SolidBox& box = boxes_[of_kind(leaf)];
            const bool upper = (part & 1) != 0;
            const Vec3& normal = box.upper_normals[part >> 1];
            on_plane(upper ? box.upper_corner : box.lower_corner, upper ? normal : -normal);
            break;
        }
        case SolidPart::Kind::HalfSpace: {
            const SolidHalfSpace& half = half_spaces_[of_kind(leaf)];
            on_plane(half.point, half.normal);
            break;
        }
        case SolidPart::Kind::Mesh: {
            const MeshSurface on_mesh =
                mesh_span_end_surface(*meshes_[of_kind(leaf)], ray, t, part == 1, tolerance(object, ray));
            round = on_mesh.round;
            out.shading_normal = on_mesh.shading_normal;
            break;
        }
        case SolidPart::Kind::Solid: break;
    }
    if (kind_of(leaf) != SolidPart::Kind::Mesh) out.shading_normal = round.normal;
    if (face & 1) round.normal = -round.normal, out.shading_normal = -out.shading_normal;
    // Back in the world: one more rounding of each coordinate.
    round.point += shift;
    round.error = (1 + gamma(1)) * round.error + gamma(1) * abs_each(round.point);
    return out;
}

}  // namespace tracer
