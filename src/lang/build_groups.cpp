// Groups and the shapes they place: a group's placement checked once and turned into transform
// steps, appended after each shape's own; spheres, planes and lights placed by them.
#include <cmath>

#include "lang/schema.h"
#include "lang/validator.h"
#include "scene/placement.h"

namespace tracer {

bool Validator::add_group_steps(const Block& block, Placed& out) {
    for (const Group* group = block.group.get(); group; group = group->outer.get()) {
        auto [entry, first] = group_steps_.try_emplace(group);
        GroupSteps& known = entry->second;
        if (first) {
            kept_ = true;
            // Its placement, checked against the group's table as any block's body.
            known.group = group == block.group.get() ? block.group : nullptr;
            Fields fields(group_spec());
            Placed placed;
            known.ok = !group->broken && check_body(group->placement, group_spec(), group->keyword, fields) &&
                       build_placement(fields, placed);
            if (placed.scale != dvec3(1.0)) known.steps.push_back({TransformStep::Kind::Scale, placed.scale, 0});
            if (placed.rotate_degrees != 0)
                known.steps.push_back({TransformStep::Kind::Rotate, placed.rotate_axis, placed.rotate_degrees});
            if (placed.translate != dvec3(0.0))
                known.steps.push_back({TransformStep::Kind::Translate, placed.translate, 0});
            known.steps.insert(known.steps.end(), placed.steps.begin(), placed.steps.end());
        }
        if (!known.ok) return false;
        out.steps.insert(out.steps.end(), known.steps.begin(), known.steps.end());
    }
    return true;
}

// A sphere placed stays a sphere only under one scale factor for every axis (with rotations,
// mirrors and moves): its centre is placed and its radius scaled; any other scale is an error.
void Validator::build_sphere(const Block& block, const Fields& fields) {
    Sphere sphere{fields.triple("center"), fields.number("radius"), material_index(fields)};
    const bool placed_here =
        fields.has("scale") || fields.has("rotate") || fields.has("translate") || fields.has("transform");
    if (placed_here || block.group) {
        Placed placed;
        if (!build_placement(fields, placed) || !add_group_steps(block, placed)) return;
        const Placement placement(placed);
        const glm::dmat3& m = placement.linear;
        const double size = glm::length(m[0]);
        const double tolerance = 1e-9 * size;
        bool similar = true;
        for (int i = 0; i < 3; ++i) {
            similar = similar && std::abs(glm::length(m[i]) - size) <= tolerance;
            similar = similar && std::abs(glm::dot(m[i], m[(i + 1) % 3])) <= tolerance * size;
        }
        if (!similar) {
            Diagnostic* d = diagnostics_.error(
                file_, placed_here ? block.kind_span : block.group->keyword,
                "this scales a sphere by different factors on different axes, which would make an ellipsoid; "
                "tracer draws spheres only: scale it by one factor, or use a mesh");
            if (!placed_here) Diagnostics::note(d, file_, block.kind_span, "the sphere is here");
            return;
        }
        sphere.center = placement.point(sphere.center);
        sphere.radius *= size;
        const double reach =
            std::max({std::abs(sphere.center.x), std::abs(sphere.center.y), std::abs(sphere.center.z)}) + sphere.radius;
        if (const std::string problem = placed_reach_problem("sphere", reach); !problem.empty())
            return (void)diagnostics_.error(file_, block.kind_span, problem);
    }
    scene_.spheres.push_back(sphere);
}

void Validator::build_plane(const Block& block, const Fields& fields) {
    Plane plane{fields.triple("point"), normalized(fields.triple("normal")), material_index(fields)};
    if (block.group) {
        Placed placed;
        if (!add_group_steps(block, placed)) return;
        const Placement placement(placed);
        plane.point = placement.point(plane.point);
        plane.normal = normalized(placement.normal * plane.normal);
    }
    scene_.planes.push_back(plane);
}

}  // namespace tracer
