// Round shapes (sphere, cylinder, cone, disc): placed into world coordinates here, since a map
// that scales every axis by one factor (with rotations, mirrors and moves) keeps them round;
// any other scale is an error.
#include <algorithm>
#include <cmath>

#include "lang/internal/scene_assembly.h"
#include "lang/schema.h"
#include "scene/placement.h"

namespace tracer {
namespace {

// The one factor by which `linear` scales every direction, or 0 if it scales directions by
// different factors (to 1e-9).
double similarity_size(const glm::dmat3& linear) {
    const double size = glm::length(linear[0]);
    const double tolerance = 1e-9 * size;
    for (int i = 0; i < 3; ++i) {
        if (std::abs(glm::length(linear[i]) - size) > tolerance) return 0;
        if (std::abs(glm::dot(linear[i], linear[(i + 1) % 3])) > tolerance * size) return 0;
    }
    return size;
}

// What a round shape becomes when scaled unevenly.
std::string stretched(std::string_view what) {
    if (what == "sphere") return "an ellipsoid";
    if (what == "disc") return "an ellipse";
    return "an elliptic " + std::string(what);
}

}  // namespace

bool place_round(SceneAssembly& a, const Block& block, const Fields& fields, std::string_view what, Placement& out,
                 double& size) {
    out = Placement();
    size = 1;
    const bool placed_here = !fields.steps().empty();
    if (!placed_here && !block.group) return true;
    Placed placed;
    if (!build_placement(a, fields, placed) || !add_group_steps(a, block, placed) ||
        !check_placed_scale(a, block, placed))
        return false;
    out = Placement(placed);
    size = similarity_size(out.linear);
    if (size > 0) return true;
    const std::string name(what);
    Diagnostic* d = a.diagnostics.error(a.file, placed_here ? block.kind_span : block.group->keyword,
                                        "this scales a " + name +
                                            " by different factors on different axes, which would "
                                            "make " +
                                            stretched(what) + "; tracer draws " + (what == "sphere" ? "" : "round ") +
                                            name + "s only: scale it by one factor, or use a mesh");
    if (!placed_here) Diagnostics::note(d, a.file, block.kind_span, "the " + name + " is here");
    return false;
}

// False (reported) if a round shape around `points` with `radius` reaches beyond +-1e30.
bool check_round_reach(SceneAssembly& a, const Block& block, std::string_view what, std::initializer_list<dvec3> points,
                       double radius) {
    double reach = 0;
    for (const dvec3& p : points) reach = std::max({reach, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    const std::string problem = placed_reach_problem(what, reach + radius);
    if (problem.empty()) return true;
    a.diagnostics.error(a.file, block.kind_span, problem);
    return false;
}

void build_sphere(SceneAssembly& a, const Block& block, const Fields& fields) {
    Sphere sphere{fields.triple("center"), fields.number("radius"), material_index(a, fields)};
    Placement placement;
    double size = 1;
    if (!place_round(a, block, fields, "sphere", placement, size)) return;
    sphere.center = placement.point(sphere.center);
    sphere.radius *= size;
    if (!check_round_reach(a, block, "sphere", {sphere.center}, sphere.radius)) return;
    const int solid = block.group ? solid_of(a, block) : kNoSolid;
    place_material(a, solid == kNoSolid ? ShapeList::Spheres : ShapeList::SolidSpheres, sphere.material, placement);
    if (solid == kNoSolid) return a.scene.spheres.push_back(sphere);
    add_solid_part(a, solid, SolidPart::Kind::Sphere, a.scene.solid_spheres.size());
    a.scene.solid_spheres.push_back(sphere);
}

// A cylinder is a cone with one radius.
void build_cone(SceneAssembly& a, const Block& block, const Fields& fields) {
    const std::string_view what = block.kind;
    const bool cylinder = what == "cylinder";
    Cone cone;
    cone.base = fields.triple("base");
    cone.top = fields.triple("top");
    cone.base_radius = fields.number(cylinder ? "radius" : "base_radius");
    cone.top_radius = fields.number(cylinder ? "radius" : "top_radius");
    cone.caps = fields.boolean("caps");
    cone.material = material_index(a, fields);
    if (cone.base == cone.top)
        return (void)a.diagnostics.error(
            a.file, fields.value_span("top"),
            "'top' must differ from 'base': they are the ends of the " + std::string(what) + "'s axis");
    if (!cylinder) {
        if (cone.base_radius == 0 && cone.top_radius == 0)
            return (void)a.diagnostics.error(a.file, fields.value_span("base_radius"),
                                             "a cone needs a radius above 0 at one end at least");
        for (std::string_view radius : {"base_radius", "top_radius"}) {
            const double value = fields.number(radius);
            if (value == 0 || value >= kSmallestSize) continue;
            return (void)a.diagnostics.error(
                a.file, fields.has(radius) ? fields.value_span(radius) : block.kind_span,
                "'" + std::string(radius) + "' must be 0 (a point) or at least 1e-30, found " + format_number(value));
        }
    }
    Placement placement;
    double size = 1;
    if (!place_round(a, block, fields, what, placement, size)) return;
    cone.base = placement.point(cone.base);
    cone.top = placement.point(cone.top);
    cone.base_radius *= size;
    cone.top_radius *= size;
    if (cone.base == cone.top)  // placed so small that both ends round to one point
        return (void)a.diagnostics.error(a.file, block.kind_span,
                                         "this " + std::string(what) + " is scaled so small that its ends meet");
    if (!check_round_reach(a, block, what, {cone.base, cone.top}, std::max(cone.base_radius, cone.top_radius))) return;
    const int solid = block.group ? solid_of(a, block) : kNoSolid;
    if (solid != kNoSolid && !cone.caps)
        return (void)a.diagnostics.error(a.file, fields.has("caps") ? fields.value_span("caps") : block.kind_span,
                                         "a " + std::string(what) +
                                             " without caps has no inside, and cannot be part of a solid: "
                                             "remove 'caps false'");
    place_material(a, solid == kNoSolid ? ShapeList::Cones : ShapeList::SolidCones, cone.material, placement);
    if (solid == kNoSolid) return a.scene.cones.push_back(cone);
    add_solid_part(a, solid, SolidPart::Kind::Cone, a.scene.solid_cones.size());
    a.scene.solid_cones.push_back(cone);
}

void build_disc(SceneAssembly& a, const Block& block, const Fields& fields) {
    Disc disc{fields.triple("center"), normalized(fields.triple("normal")), fields.number("radius"),
              material_index(a, fields)};
    Placement placement;
    double size = 1;
    if (!place_round(a, block, fields, "disc", placement, size)) return;
    disc.center = placement.point(disc.center);
    disc.normal = normalized(placement.normal * disc.normal);
    disc.radius *= size;
    if (!check_round_reach(a, block, "disc", {disc.center}, disc.radius)) return;
    place_material(a, ShapeList::Discs, disc.material, placement);
    a.scene.discs.push_back(disc);
}

}  // namespace tracer
