// Groups: a group's placement checked once and turned into transform steps, appended after each
// shape's own; planes placed by them (round shapes: build_round.cpp).
#include <algorithm>
#include <cstdio>

#include <glm/common.hpp>

#include "lang/internal/scene_assembly.h"
#include "lang/schema.h"
#include "scene/placement.h"

namespace tracer {

bool add_group_steps(SceneAssembly& a, const Block& block, Placed& out) {
    for (const Group* group = block.group.get(); group; group = group->outer.get()) {
        auto [entry, first] = a.group_steps.try_emplace(group);
        SceneAssembly::GroupSteps& known = entry->second;
        if (first) {
            a.kept = true;
            // Its placement, checked against the group's table as any block's body.
            known.group = group == block.group.get() ? block.group : nullptr;
            Fields fields(group_spec());
            Placed placed;
            known.ok = !group->broken && a.check_group_placement(*group, fields) && build_placement(a, fields, placed);
            known.steps = placement_steps(placed);
        }
        if (!known.ok) return false;
        out.steps.insert(out.steps.end(), known.steps.begin(), known.steps.end());
    }
    return true;
}

bool check_placed_scale(SceneAssembly& a, const Block& block, const Placed& placed) {
    // Bounds of the composed map's scale on any axis: the products of each step's smallest and
    // largest factors (a rotation between steps changes which axis, never these bounds).
    const dvec3 own = glm::abs(placed.scale);
    double smallest = std::min({own.x, own.y, own.z}), largest = std::max({own.x, own.y, own.z});
    for (const TransformStep& step : placed.steps) {
        if (step.kind != TransformStep::Kind::Scale) continue;
        const dvec3 size = glm::abs(step.vector);
        smallest *= std::min({size.x, size.y, size.z});
        largest *= std::max({size.x, size.y, size.z});
    }
    if (smallest >= kSmallestSize && largest <= kLargestMagnitude) return true;
    char text[64];
    std::snprintf(text, sizeof text, "%.3g", smallest < kSmallestSize ? smallest : largest);
    Diagnostic* d = a.diagnostics.error(a.file, block.kind_span,
                                        "this " + block.kind + " is scaled by " + text +
                                            " on some axis by its own steps and its groups' together; sizes "
                                            "must stay between 1e-30 and 1e30");
    if (block.group) Diagnostics::note(d, a.file, block.group->keyword, "the innermost group placing it is here");
    return false;
}

void build_plane(SceneAssembly& a, const Block& block, const Fields& fields) {
    Plane plane{fields.triple("point"), normalized(fields.triple("normal")), material_index(a, fields)};
    if (block.group) {
        Placed placed;
        if (!add_group_steps(a, block, placed)) return;
        const Placement placement(placed);
        plane.point = placement.point(plane.point);
        plane.normal = normalized(placement.normal * plane.normal);
        const int solid = solid_of(a, block);
        place_material(a, solid == kNoSolid ? ShapeList::Planes : ShapeList::HalfSpaces, plane.material, placement);
        if (solid != kNoSolid) {
            add_solid_part(a, solid, SolidPart::Kind::HalfSpace, a.scene.half_spaces.size());
            return a.scene.half_spaces.push_back(plane);
        }
    }
    a.scene.planes.push_back(plane);
}

}  // namespace tracer
