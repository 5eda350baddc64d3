#include "accel/solid_objects.h"

#include <algorithm>
#include <cmath>
#include <span>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "accel/solid_leaves.h"
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

// The box around a disc across the unit `axis` (a cone's cap).
Bounds disc_bounds(const glm::dvec3& center, const glm::dvec3& axis, double radius) {
    const glm::dvec3 extent = radius * glm::sqrt(glm::max(glm::dvec3(1.0) - axis * axis, glm::dvec3(0.0)));
    return {Vec3(center - extent), Vec3(center + extent)};
}

SolidLeaf sphere_leaf(const Sphere& sphere) {
    SolidLeaf leaf;
    leaf.kind = SolidPart::Kind::Sphere;
    leaf.material = sphere.material;
    leaf.center = Vec3(sphere.center);
    leaf.radius = Real(sphere.radius);
    leaf.bounds = {leaf.center - leaf.radius, leaf.center + leaf.radius};
    return leaf;
}

SolidLeaf box_leaf(const Box& box) {
    SolidLeaf leaf;
    leaf.kind = SolidPart::Kind::Box;
    leaf.material = box.material;
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
    for (int corner = 0; corner < 8; ++corner)
        leaf.bounds.extend(Vec3(placement.point({corner & 1 ? box.max.x : box.min.x, corner & 2 ? box.max.y : box.min.y,
                                                 corner & 4 ? box.max.z : box.min.z})));
    return leaf;
}

SolidLeaf cone_leaf(const Cone& cone) {
    SolidLeaf leaf;
    leaf.kind = SolidPart::Kind::Cone;
    leaf.material = cone.material;
    leaf.cone = make_cone_shape(cone.base, cone.top, cone.base_radius, cone.top_radius, true);
    const glm::dvec3 axis = glm::normalize(cone.top - cone.base);
    leaf.bounds = disc_bounds(cone.base, axis, cone.base_radius);
    leaf.bounds.extend(disc_bounds(cone.top, axis, cone.top_radius));
    return leaf;
}

SolidLeaf half_space_leaf(const Plane& plane) {
    SolidLeaf leaf;
    leaf.kind = SolidPart::Kind::HalfSpace;
    leaf.material = plane.material;
    leaf.point = Vec3(plane.point);
    leaf.normal = Vec3(plane.normal);
    leaf.bounds = {Vec3(-kInfinity), Vec3(kInfinity)};
    // Across an axis, it is bounded on that axis.
    for (int axis = 0; axis < 3; ++axis) {
        if (std::abs(plane.normal[axis]) != 1) continue;
        if (plane.normal[axis] > 0)
            leaf.bounds.upper[axis] = Real(plane.point[axis]);
        else
            leaf.bounds.lower[axis] = Real(plane.point[axis]);
    }
    leaf.reach = std::max({std::abs(leaf.point.x), std::abs(leaf.point.y), std::abs(leaf.point.z)});
    return leaf;
}

Bounds overlap(const Bounds& a, const Bounds& b) {
    return {glm::max(a.lower, b.lower), glm::min(a.upper, b.upper)};
}

bool is_empty(const Bounds& box) {
    return !(box.lower.x <= box.upper.x && box.lower.y <= box.upper.y && box.lower.z <= box.upper.z);
}

// The scratch of the spans' sweep, one per thread: a ray allocates nothing once it has run.
struct SpanScratch {
    std::vector<SolidSpan> spans, combined;
    std::vector<uint32_t> starts;
};
thread_local SpanScratch scratch;

}  // namespace

SolidObjects::SolidObjects(const SceneDescription& scene) {
    add_leaves(scene);
    // Each solid's bounds, from its parts' (a nested solid comes after the solid it is part of).
    std::vector<Bounds> solid_bounds(scene.solids.size());
    for (size_t i = scene.solids.size(); i-- > 0;) {
        const Solid& solid = scene.solids[i];
        Bounds box;
        bool first = true;
        for (const SolidPart& part : solid.parts) {
            const Bounds& of_part = part.kind == SolidPart::Kind::Solid
                                        ? solid_bounds[part.index]
                                        : leaves_[first_leaf_of_kind_[size_t(part.kind)] + part.index].bounds;
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
        if (!scene.solids[i].nested) add_program(scene, i, solid_bounds);
}

void SolidObjects::add_leaves(const SceneDescription& scene) {
    first_leaf_of_kind_.assign(size_t(SolidPart::Kind::Solid) + 1, 0);
    first_leaf_of_kind_[size_t(SolidPart::Kind::Sphere)] = uint32_t(leaves_.size());
    for (const Sphere& sphere : scene.solid_spheres) leaves_.push_back(sphere_leaf(sphere));
    first_leaf_of_kind_[size_t(SolidPart::Kind::Box)] = uint32_t(leaves_.size());
    for (const Box& box : scene.solid_boxes) leaves_.push_back(box_leaf(box));
    first_leaf_of_kind_[size_t(SolidPart::Kind::Cone)] = uint32_t(leaves_.size());
    for (const Cone& cone : scene.solid_cones) leaves_.push_back(cone_leaf(cone));
    first_leaf_of_kind_[size_t(SolidPart::Kind::HalfSpace)] = uint32_t(leaves_.size());
    for (const Plane& plane : scene.half_spaces) leaves_.push_back(half_space_leaf(plane));
    for (SolidLeaf& leaf : leaves_)
        if (leaf.kind != SolidPart::Kind::HalfSpace) leaf.reach = reach_of(leaf.bounds);
}

// The solid's program, walked depth first without recursion (solids may nest 10^4 deep): each
// leaf, and after each part but a solid's first, the solid's operation.
void SolidObjects::add_program(const SceneDescription& scene, uint32_t root, const std::vector<Bounds>& solid_bounds) {
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
        object.reach = std::max(object.reach, leaves_[leaf].reach);
        steps_.push_back({Step::Kind::Leaf, SolidOp::Union, leaf});
        if (frame.next >= 1) steps_.push_back({Step::Kind::Combine, solid.op, 0});
    }
    object.steps = uint32_t(steps_.size()) - object.first_step;
    objects_.push_back(object);
}

bool SolidObjects::bounded(uint32_t solid) const {
    const Bounds& box = objects_[solid].bounds;
    for (int axis = 0; axis < 3; ++axis)
        if (!std::isfinite(box.lower[axis]) || !std::isfinite(box.upper[axis])) return false;
    return true;
}

std::optional<SolidSpan> SolidObjects::leaf_span(uint32_t index, const Ray& ray) const {
    const SolidLeaf& leaf = leaves_[index];
    switch (leaf.kind) {
        case SolidPart::Kind::Sphere: return sphere_span(ray, leaf.center, leaf.radius, index);
        case SolidPart::Kind::Box: {
            const Ray own{leaf.to_object * (ray.origin - leaf.translate), leaf.to_object * ray.direction};
            return box_span(own, leaf.lower, leaf.upper, index);
        }
        case SolidPart::Kind::Cone: return cone_span(ray, leaf.cone, index);
        case SolidPart::Kind::HalfSpace: return half_space_span(ray, leaf.point, leaf.normal, index);
        case SolidPart::Kind::Solid: break;
    }
    return std::nullopt;
}

void SolidObjects::run(const Object& object, const Ray& ray, Real tolerance, std::vector<SolidSpan>& out) const {
    std::vector<uint32_t>& starts = scratch.starts;
    std::vector<SolidSpan>& combined = scratch.combined;
    out.clear();
    starts.clear();
    for (uint32_t i = object.first_step; i < object.first_step + object.steps; ++i) {
        const Step& step = steps_[i];
        if (step.kind != Step::Kind::Combine) {
            starts.push_back(uint32_t(out.size()));
            if (step.kind == Step::Kind::Leaf)
                if (auto span = leaf_span(step.leaf, ray)) out.push_back(*span);
            continue;
        }
        const uint32_t b = starts.back();
        starts.pop_back();
        const uint32_t a = starts.back();
        const bool a_empty = a == b, b_empty = b == out.size();
        // Nothing to cut from or to overlap; or nothing to add, cut or overlap with.
        if (a_empty && step.op != SolidOp::Union) {
            out.resize(a);
            continue;
        }
        if (b_empty) {
            if (step.op == SolidOp::Intersection) out.resize(a);
            continue;
        }
        combined.clear();
        combine_spans(step.op, std::span(out.data() + a, b - a), std::span(out.data() + b, out.size() - b), tolerance,
                      combined);
        out.resize(a);
        out.insert(out.end(), combined.begin(), combined.end());
    }
}

std::optional<SolidHit> SolidObjects::nearest(uint32_t solid, const Ray& ray, Interval range) const {
    const Object& object = objects_[solid];
    const Vec3 o = abs_each(ray.origin);
    // Crossings closer than this are one place; one this close to the origin is the surface a
    // spawned ray leaves (its t computed from the moved origin may round either way).
    const Real tolerance = gamma(32) * (std::max({o.x, o.y, o.z}) + object.reach);
    std::vector<SolidSpan>& spans = scratch.spans;
    run(object, ray, tolerance, spans);
    const Real from = std::max(range.min, tolerance);
    for (const SolidSpan& span : spans)
        for (const SpanEnd& end : {span.enter, span.leave}) {
            if (!(end.t < range.max)) return std::nullopt;
            if (end.t > from) return SolidHit{end.t, pack_solid_face(end)};
        }
    return std::nullopt;
}

SolidSurface SolidObjects::surface(const Ray& ray, Real t, uint32_t face) const {
    const SolidLeaf& leaf = leaves_[face >> 4];
    const uint32_t part = (face >> 1) & 7;
    SolidSurface out;
    out.material = leaf.material;
    RoundSurface& round = out.round;
    // A point put back on a flat face: projected onto its plane.
    auto on_plane = [&](const Vec3& point, const Vec3& normal) {
        const Vec3 along_ray = ray.at(t);
        round.point = along_ray - glm::dot(along_ray - point, normal) * normal;
        round.error = gamma(8) * (abs_each(round.point) + abs_each(point));
        round.normal = normal;
    };
    switch (leaf.kind) {
        case SolidPart::Kind::Sphere: {
            const Vec3 from_center = ray.at(t) - leaf.center;
            const Real length = glm::length(from_center);
            round.normal = length > 0 ? from_center * (1 / length) : Vec3(0, 0, 1);
            const Vec3 on_sphere = round.normal * leaf.radius;
            round.point = leaf.center + on_sphere;
            round.error = gamma(6) * (abs_each(leaf.center) + abs_each(on_sphere));
            break;
        }
        case SolidPart::Kind::Cone: round = cone_surface(ray, leaf.cone, t, part); break;
        case SolidPart::Kind::Box: {
            const bool upper = (part & 1) != 0;
            const Vec3& normal = leaf.upper_normals[part >> 1];
            on_plane(upper ? leaf.upper_corner : leaf.lower_corner, upper ? normal : -normal);
            break;
        }
        case SolidPart::Kind::HalfSpace: on_plane(leaf.point, leaf.normal); break;
        case SolidPart::Kind::Solid: break;
    }
    if (face & 1) round.normal = -round.normal;
    return out;
}

}  // namespace tracer
