// World's ray queries, defined inline (included by world.h): they are the innermost loop of
// every ray, and as calls of their own their results pass through memory and the spheres are
// tested out of line (docs/bench/code-figures.md).
#pragma once

#include "accel/geometry.h"
#include "accel/triangle.h"
#include "accel/world.h"

namespace tracer {

[[gnu::always_inline]] inline bool World::hit_instance(uint32_t index, uint32_t object, const Ray& ray, Interval& range,
                                                       Hit& hit, SearchCounts& counts) const {
    const MeshInstance& instance = instances_[index];
    const MeshAccel& mesh = meshes_[instance.mesh];
    MeshHit mesh_hit;
    const bool found = instance.placed ? mesh.intersect(ray, range, mesh_hit, counts.triangles)
                                       : mesh.intersect(instance.to_mesh(ray), range, mesh_hit, counts.triangles);
    if (found)
        hit = {object != kObjectOfTriangle ? object : mesh.tag_of(mesh_hit.slot), mesh_hit.slot, range.max,
               mesh_hit.hit.u, mesh_hit.hit.v};
    return found;
}

inline bool World::instance_blocks(uint32_t entry, const Ray& ray, Interval range, SearchCounts& counts,
                                   Occluder& blocker) const {
    const MeshInstance& instance = instances_[bounded_[entry].index];
    const MeshAccel& mesh = meshes_[instance.mesh];
    const bool blocked = instance.placed
                             ? mesh.occluded(ray, range, counts.triangles, blocker.triangles)
                             : mesh.occluded(instance.to_mesh(ray), range, counts.triangles, blocker.triangles);
    if (blocked) blocker.entry = entry;
    return blocked;
}

// hit_instance's sibling for any bounded object but a mesh instance: a sphere, cone or disc.
[[gnu::always_inline]] inline bool World::hit_bounded(const Bounded& b, const Ray& ray, Interval& range, Hit& hit,
                                                      SearchCounts& counts) const {
    if (b.kind == ObjectKind::Sphere) {
        const auto t = intersect_sphere(ray, b.center, b.radius, range);
        if (!t) return false;
        range.max = *t;
        hit = {b.object, 0, *t, 0, 0};
        return true;
    }
    if (b.kind == ObjectKind::Cone) {
        const auto found = intersect_cone(ray, cones_[b.index], range);
        if (!found) return false;
        range.max = found->t;
        hit = {b.object, found->part, found->t, 0, 0};
        return true;
    }
    if (b.kind == ObjectKind::Disc) {
        const auto t = intersect_disc(ray, discs_[b.index], range);
        if (!t) return false;
        range.max = *t;
        hit = {b.object, 0, *t, 0, 0};
        return true;
    }
    if (b.kind == ObjectKind::Solid) {
        const auto found = solids_.nearest(b.index, ray, range);
        if (!found) return false;
        range.max = found->t;
        hit = {b.object, found->face, found->t, 0, 0};
        return true;
    }
    return hit_instance(b.index, b.object, ray, range, hit, counts);
}

// True if the bounded object `entry` lies along `ray` within `range`; it becomes `blocker`.
inline bool World::bounded_blocks(uint32_t entry, const Ray& ray, Interval range, SearchCounts& counts,
                                  Occluder& blocker) const {
    const Bounded& b = bounded_[entry];
    bool blocked = false;
    switch (b.kind) {
        case ObjectKind::MeshInstance: return instance_blocks(entry, ray, range, counts, blocker);
        case ObjectKind::Sphere: blocked = intersect_sphere(ray, b.center, b.radius, range).has_value(); break;
        case ObjectKind::Cone: blocked = intersect_cone(ray, cones_[b.index], range).has_value(); break;
        case ObjectKind::Disc: blocked = intersect_disc(ray, discs_[b.index], range).has_value(); break;
        case ObjectKind::Solid: blocked = solids_.nearest(b.index, ray, range).has_value(); break;
        case ObjectKind::Plane: break;
    }
    if (blocked) blocker = {entry, {}};
    return blocked;
}

inline bool World::occluder_blocks(const Occluder& occluder, const Ray& ray, Interval range, SearchCounts& counts,
                                   uint32_t left_behind) const {
    const Bounded& b = bounded_[occluder.entry];
    if (b.object == left_behind) return false;
    if (b.kind == ObjectKind::Sphere) {
        ++counts.objects.primitive_tests;
        return intersect_sphere(ray, b.center, b.radius, range).has_value();
    }
    if (b.kind != ObjectKind::MeshInstance) {
        ++counts.objects.primitive_tests;
        Occluder ignored;
        return bounded_blocks(occluder.entry, ray, range, counts, ignored);
    }
    counts.triangles.primitive_tests += occluder.triangles.count;
    const MeshInstance& instance = instances_[b.index];
    const MeshAccel& mesh = meshes_[instance.mesh];
    return instance.placed ? mesh.blocks(occluder.triangles, ray, range)
                           : mesh.blocks(occluder.triangles, instance.to_mesh(ray), range);
}

[[gnu::always_inline]] inline bool World::nearest_plane(const Ray& ray, Interval& range, Hit& hit) const {
    bool found = false;
    for (const PlaneShape& p : planes_) {
        if (auto t = intersect_plane(ray, p.point, p.normal, range)) {
            range.max = *t;
            hit = {p.object, 0, *t, 0, 0};
            found = true;
        }
    }
    for (const UnboundedSolid& solid : unbounded_solids_) {
        if (auto solid_hit = solids_.nearest(solid.index, ray, range)) {
            range.max = solid_hit->t;
            hit = {solid.object, solid_hit->face, solid_hit->t, 0, 0};
            found = true;
        }
    }
    return found;
}

[[gnu::always_inline]] inline bool World::nearest_sphere_or_plane(const Ray& ray, Interval& range, Hit& hit,
                                                                  uint32_t left_behind) const {
    bool found = false;
    for (uint32_t i = 0; i < sphere_count_; ++i) {
        const Bounded& s = bounded_[i];
        if (s.object == left_behind) continue;
        if (auto t = intersect_sphere(ray, s.center, s.radius, range)) {
            range.max = *t;
            hit = {s.object, 0, *t, 0, 0};
            found = true;
        }
    }
    return nearest_plane(ray, range, hit) || found;
}

[[gnu::always_inline]] inline bool World::may_meet_entry(size_t entry, const Ray& ray, Interval range) const {
    const Bounded& b = bounded_[entry];
    return line_may_meet_sphere(ray, b.center, b.radius * b.radius) &&
           ray_may_meet_box(ray, linear_boxes_[entry], range);
}

[[gnu::always_inline]] inline bool World::nearest_one_by_one(const Ray& ray, Interval& range, Hit& hit,
                                                             SearchCounts& counts, uint32_t left_behind) const {
    // Spheres, planes, then meshes (objects are numbered in this order; bounded_ lists the
    // spheres, then the meshes).
    bool found = nearest_sphere_or_plane(ray, range, hit, left_behind);
    for (size_t i = sphere_count_; i < bounded_.size(); ++i) {
        const Bounded& b = bounded_[i];
        if (b.object != left_behind && may_meet_entry(i, ray, range))
            found = hit_bounded(b, ray, range, hit, counts) || found;
    }
    counts.objects.primitive_tests += bounded_.size();
    return found;
}

[[gnu::always_inline]] inline std::optional<Hit> World::nearest_hit(const Ray& ray, Interval range,
                                                                    SearchCounts& counts, uint32_t left_behind) const {
    // Two records, so that the one-by-one search's can stay in registers: the BVH's test, out
    // of line, holds the address of its own (docs/bench/code-figures.md).
    if (linear_) {
        Hit hit;
        if (!nearest_one_by_one(ray, range, hit, counts, left_behind)) return std::nullopt;
        return hit;
    }
    // Each hit shrinks range.max, so later objects only count when they are nearer. Planes
    // first: a floor's hit lets the top level skip every box behind it.
    Hit hit;
    bool found = nearest_plane(ray, range, hit);
    LastCone last_cone;
    auto test = [&](uint32_t i, Interval& r) {
        const Bounded& b = bounded_[i];
        if (b.object == left_behind || !last_cone.untested(b)) return false;
        if (b.kind == ObjectKind::MeshInstance) return hit_instance(b.index, b.object, ray, r, hit, counts);
        return hit_bounded(b, ray, r, hit, counts);
    };
    found = top_.closest(ray, range, counts.objects, test) || found;
    if (!found) return std::nullopt;
    return hit;
}

// surface's step for a sphere: the point, its error bound and the normal; a sphere is convex.
[[gnu::always_inline]] inline void World::sphere_surface(const Ray& ray, const Hit& hit, SurfaceHit& out) const {
    const Object& object = objects_[hit.object];
    const Bounded& s = bounded_[object.index];
    if constexpr (kRobust) {
        // The point put back on the sphere (pbrt-v4): its error is then gamma(5) of the
        // offset from the center, plus the rounding of adding the center.
        const Vec3 from_center = ray.at(hit.t) - s.center;
        const Real length = glm::length(from_center);
        out.normal = length > 0 ? from_center * (1 / length) : Vec3(0, 0, 1);
        const Vec3 on_sphere = out.normal * s.radius;
        out.point = s.center + on_sphere;
        out.error = gamma(6) * (abs_each(s.center) + abs_each(on_sphere));
    } else {
        out.normal = (out.point - s.center) / s.radius;
    }
    out.geometric_normal = out.normal;
    out.convex_object = hit.object;
}

// surface's step for a mesh instance: the point (placed, with its error bound), the face's
// and the shading normal.
[[gnu::always_inline]] inline void World::mesh_surface(const Ray& ray, const Hit& hit, SurfaceHit& out) const {
    const Object& object = objects_[hit.object];
    const MeshInstance& instance = instances_[object.index];
    const MeshAccel& mesh = meshes_[instance.mesh];
    if constexpr (kRobust) out.point = mesh.surface_point(hit.primitive, hit.u, hit.v, out.error);
    // A mesh on an axis plane, as built: rays leaving it skip it (if it is one object).
    if (instance.placed && mesh.on_axis_plane()) out.convex_object = hit.object, out.flat = true;
    out.geometric_normal = mesh.geometric_normal(hit.primitive);
    if (instance.placed) {
        out.normal = mesh.shading_normal(hit.primitive, hit.u, hit.v);
    } else {
        // Normals map by the inverse transpose of the placement: transpose(to_object).
        const Mat3 normal_map = glm::transpose(instance.to_object);
        out.normal = mesh.shading_normal(hit.primitive, hit.u, hit.v, normal_map);
        out.geometric_normal = normalize_or_zero(normal_map * out.geometric_normal);
        if constexpr (kRobust) {
            // The point placed, its error grown by the placing's roundings (pbrt-v4's
            // transform of a point with an error bound).
            Mat3 abs_to_world;
            for (int c = 0; c < 3; ++c) abs_to_world[c] = abs_each(instance.to_world[c]);
            out.error = (1 + gamma(3)) * (abs_to_world * out.error) +
                        gamma(3) * (abs_to_world * abs_each(out.point) + abs_each(instance.translate));
            out.point = instance.to_world * out.point + instance.translate;
        }
    }
    // A zero-area sliver: its vertex normals stand for the face's; if they cancel too,
    // it faces the ray.
    if (out.geometric_normal == Vec3(0)) [[unlikely]]
        out.geometric_normal = out.normal;
    if (out.normal == Vec3(0)) [[unlikely]] {
        out.normal = -normalize_or_zero(ray.direction);
        out.geometric_normal = out.normal;
    }
}

[[gnu::always_inline]] inline SurfaceHit World::surface(const Ray& ray, const Hit& hit) const {
    const Object& object = objects_[hit.object];
    SurfaceHit out;
    out.t = hit.t;
    out.material = object.material;
    // The naive rule (TRACER_ROBUST=OFF) takes the point along the ray and needs no error bound.
    if constexpr (!kRobust) out.point = ray.at(hit.t), out.error = Vec3(0);
    switch (object.kind) {
        case ObjectKind::Sphere: sphere_surface(ray, hit, out); break;
        case ObjectKind::Plane: {
            const PlaneShape& p = planes_[object.index];
            if constexpr (kRobust) {
                // The point projected onto the plane; the bound covers that projection and the
                // plane test of a ray leaving it.
                const Vec3 along_ray = ray.at(hit.t);
                out.point = along_ray - glm::dot(along_ray - p.point, p.normal) * p.normal;
                out.error = gamma(8) * (abs_each(out.point) + abs_each(p.point));
            }
            out.normal = p.normal;
            out.geometric_normal = p.normal;
            break;
        }
        case ObjectKind::Cone:
        case ObjectKind::Disc: {
            const RoundSurface round = object.kind == ObjectKind::Cone
                                           ? cone_surface(ray, cones_[object.index], hit.t, hit.primitive)
                                           : disc_surface(ray, discs_[object.index], hit.t);
            if constexpr (kRobust) {
                out.point = round.point;
                out.error = round.error;
            }
            out.normal = round.normal;
            out.geometric_normal = round.normal;
            out.convex_object = hit.object;
            out.flat = object.kind == ObjectKind::Disc;
            if (out.normal == Vec3(0)) [[unlikely]] {  // no side to leave by: skip nothing
                out.normal = -normalize_or_zero(ray.direction);
                out.geometric_normal = out.normal;
                out.convex_object = kNoObject;
            }
            break;
        }
        case ObjectKind::MeshInstance: mesh_surface(ray, hit, out); break;
        case ObjectKind::Solid: {
            const SolidSurface solid = solids_.surface(ray, hit.t, hit.primitive);
            if constexpr (kRobust) {
                out.point = solid.round.point;
                out.error = solid.round.error;
            }
            out.normal = solid.shading_normal;
            out.geometric_normal = solid.round.normal;
            out.material = solid.material;
            if (out.normal == Vec3(0)) [[unlikely]] {  // a cone's apex: face the ray
                out.normal = -normalize_or_zero(ray.direction);
                out.geometric_normal = out.normal;
            }
            break;
        }
    }
    return out;
}

[[gnu::always_inline]] inline bool World::occluded(const Ray& ray, Interval range, SearchCounts& counts, Occluder& last,
                                                   uint32_t left_behind) const {
    if (last.entry != Occluder::kNone) {
        if (occluder_blocks(last, ray, range, counts, left_behind)) return true;
        last.entry = Occluder::kNone;
    }
    if (linear_) {
        for (uint32_t i = 0; i < sphere_count_; ++i) {
            if (bounded_[i].object != left_behind &&
                intersect_sphere(ray, bounded_[i].center, bounded_[i].radius, range)) {
                last = {i, {}};
                return true;
            }
        }
    }
    for (const PlaneShape& p : planes_)
        if (intersect_plane(ray, p.point, p.normal, range)) return true;
    for (const UnboundedSolid& solid : unbounded_solids_)
        if (solids_.nearest(solid.index, ray, range)) return true;
    if (linear_) {
        counts.objects.primitive_tests += sphere_count_;
        for (size_t i = sphere_count_; i < bounded_.size(); ++i) {
            const Bounded& b = bounded_[i];
            ++counts.objects.primitive_tests;
            if (b.object != left_behind && may_meet_entry(i, ray, range) &&
                bounded_blocks(uint32_t(i), ray, range, counts, last))
                return true;
        }
        return false;
    }
    // Through the BVH the ray has entered an instance's box before it is tested, so the
    // bounding sphere (which holds the box) would rule nothing out.
    LastCone last_cone;
    auto test = [&](uint32_t i, Interval& r) {
        const Bounded& b = bounded_[i];
        if (b.object == left_behind || !last_cone.untested(b)) return false;
        if (b.kind == ObjectKind::MeshInstance) return instance_blocks(i, ray, r, counts, last);
        if (b.kind != ObjectKind::Sphere) return bounded_blocks(i, ray, r, counts, last);
        if (!intersect_sphere(ray, b.center, b.radius, r)) return false;
        last = {i, {}};
        return true;
    };
    return top_.any(ray, range, counts.objects, test);
}

}  // namespace tracer
