// The scene description in the making: free functions turn each block's checked fields
// (checked_fields.h, from the validator) into its part of the description, and report what
// the values alone could not show (a camera looking along its up, a triangle with no area, a
// shape placed beyond the renderer's range). build_scene.cpp: materials, render settings,
// camera, meshes, flat shapes; build_round.cpp: spheres, cones, discs; build_groups.cpp:
// groups' steps, planes. Internal to lang/.
#pragma once

#include <functional>
#include <initializer_list>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/diagnostics.h"
#include "base/source.h"
#include "lang/internal/checked_fields.h"
#include "lang/internal/evaluated_scene.h"
#include "scene/placement.h"
#include "scene/scene.h"
#include "scene/triangle_mesh.h"

namespace tracer {

// The shapes' lists, for the materials of shapes placed before their material's block.
enum class ShapeList : uint8_t {
    Spheres,
    Planes,
    Meshes,
    Triangles,
    Quads,
    Boxes,
    Cones,
    Discs,
    SolidSpheres,
    SolidBoxes,
    SolidCones,
    HalfSpaces,
    SolidMeshes
};

// The solid of a shape made outside every solid (solid_of).
constexpr int kNoSolid = -1;

struct SceneAssembly {
    // Checks a group's placement against the group table, filling `fields` (the validator's
    // check_body): asked the first time a block placed by the group is built.
    using CheckPlacement = std::function<bool(const Group& group, Fields& fields)>;

    SceneAssembly(const Sources& sources, Diagnostics& reports, CheckPlacement check_placement);

    const Sources& file;  // the scene file and those it includes
    Diagnostics& diagnostics;
    CheckPlacement check_group_placement;
    SceneDescription scene;

    std::map<std::string, int, std::less<>> material_by_name;  // index into scene.materials
    long long light_samples = 0;  // of the lights built so far (a point light is one), for add_light
    // Material values shared by several shapes, by their body (held, so that no other body can
    // take its address): each made into one material.
    struct SharedMaterial {
        std::shared_ptr<const Body> body;
        int index;
    };
    std::map<const Body*, SharedMaterial> value_materials;
    // Each group's own steps, by the group (held, so that no other group can take its
    // address); `ok` false if its placement was refused.
    struct GroupSteps {
        std::shared_ptr<const Group> group;
        bool ok = false;
        std::vector<TransformStep> steps;
    };
    std::map<const Group*, GroupSteps> group_steps;
    // Materials used by name before their block: a shape's material index kLaterMaterial - i
    // stands for later_materials[i], until resolve_later_materials.
    static constexpr int kLaterMaterial = -2;
    std::vector<std::string> later_materials;
    // Pattern values shared by several materials, by their body (as value_materials).
    std::map<const Body*, std::pair<std::shared_ptr<const Body>, int>> value_patterns;
    // Placed copies of patterned materials, by material and placement.
    std::map<std::pair<int, std::vector<double>>, int> placed_materials;
    struct LaterPlacement {  // a shape placed with a material not yet defined
        ShapeList list;
        size_t index;
        Affine to_object;
    };
    std::vector<LaterPlacement> later_placements;
    // The solid (an index into scene.solids, or kNoSolid: a union that is a group) each solid's
    // block stands for, by its group (held, as group_steps').
    struct SolidOfGroup {
        std::shared_ptr<const Group> group;
        int index = kNoSolid;
    };
    std::map<const Group*, SolidOfGroup> solids;
    bool kept = false;  // the block being built had a span of its kept (in the members above)
};

// Adds what one block's checked fields describe: a material, a shape, a light, the camera or
// the render settings.
void build_block(SceneAssembly& a, const Block& block, const Fields& fields);
// Gives each shape that used a material before its block that material's index (-1 if it was
// never defined: the validator reports it).
void resolve_later_materials(SceneAssembly& a);
// Records the scene's parameters, as the interpreter found them.
void set_parameters(SceneAssembly& a, const std::vector<std::pair<std::string, PlainValue>>& parameters);
// Warnings where the image cannot be what the author meant (the scene stays valid).
void warn_about_the_picture(const SceneAssembly& a);

// The builders' shared steps.
Material build_material(SceneAssembly& a, const Fields& fields, std::string name);
// A colour key that may hold a pattern (ka, kd, a checker's squares): the colour, or the
// pattern built into scene.patterns (once for a pattern value that many materials share).
Paint build_paint(SceneAssembly& a, const Fields& fields, std::string_view key);
// Gives the shape about to be added as the next of `list` the material it carries in
// `material`, placed by `placement` (own coordinates -> world): a patterned material's patterns
// move with the shape, so it gets a copy with that placement (one per material and placement).
void place_material(SceneAssembly& a, ShapeList list, int& material, const Placement& placement);
// Gives the shapes whose material was defined after them their placed copies (after
// resolve_later_materials).
void place_later_materials(SceneAssembly& a);
// The index of the shape's material: a named one, or its inline block added to the list.
int material_index(SceneAssembly& a, const Fields& fields);
// The placement and material of a mesh or flat shape; false if the placement is refused.
bool build_placed(SceneAssembly& a, const Block& block, const Fields& fields, Placed& out);
// The placement written by `fields`' scale, rotate and translate keys, or by the steps of its
// transform block (not both); false if it is refused (reported).
bool build_placement(SceneAssembly& a, const Fields& fields, Placed& out);
// Appends to `out` the steps of the groups `block` was made in, innermost first; false if a
// group's placement is refused (reported once, at the group).
bool add_group_steps(SceneAssembly& a, const Block& block, Placed& out);
// False (reported) if the placement's steps and its groups' together scale some axis below
// 1e-30 or above 1e30 (each step alone may be in range: two groups of scale 1e-20).
bool check_placed_scale(SceneAssembly& a, const Block& block, const Placed& placed);
// The placement of a round shape (sphere, cylinder, cone, disc): false if refused (reported),
// else `out` and its one scale factor `size`; the identity when nothing places the block.
bool place_round(SceneAssembly& a, const Block& block, const Fields& fields, std::string_view what, Placement& out,
                 double& size);
// False (reported) if a round shape around `points` with `radius` reaches beyond +-1e30.
bool check_round_reach(SceneAssembly& a, const Block& block, std::string_view what, std::initializer_list<dvec3> points,
                       double radius);
// False (reported) if a placed flat shape's corner leaves the renderer's range.
bool check_reach(SceneAssembly& a, const Block& block, const Placed& placed, const TriangleMesh& mesh);

// Solids (build_solids.cpp). The solid a shape made by `block` is a part of (an index into
// scene.solids), made with the solids around it the first time, or kNoSolid.
int solid_of(SceneAssembly& a, const Block& block);
// Makes the shape just added as `index` of the list of `kind` a part of `solid`.
void add_solid_part(SceneAssembly& a, int solid, SolidPart::Kind kind, size_t index);
// False (reported) if `block` is made in a solid and cannot be a part of one (a light, a quad).
bool check_solid_part(SceneAssembly& a, const Block& block);

// Every point shaded traces a shadow ray to each sample of each light: their sum is bounded by
// this (a 256 x 256 area light, or as many point lights), past which a light is refused.
constexpr long long kMostLightSamples = 65536;
// Adds `light` to the scene, or reports it at `block` if its samples take the scene's past
// kMostLightSamples.
void add_light(SceneAssembly& a, const Block& block, const Light& light);

// The builders, one per kind of block.
void build_render(SceneAssembly& a, const Block& block, const Fields& fields);
void build_camera(SceneAssembly& a, const Block& block, const Fields& fields);
void build_light(SceneAssembly& a, const Block& block, const Fields& fields);
void build_sphere(SceneAssembly& a, const Block& block, const Fields& fields);
void build_cone(SceneAssembly& a, const Block& block, const Fields& fields);
void build_disc(SceneAssembly& a, const Block& block, const Fields& fields);
void build_plane(SceneAssembly& a, const Block& block, const Fields& fields);
void build_mesh(SceneAssembly& a, const Block& block, const Fields& fields);
void build_flat_shape(SceneAssembly& a, const Block& block, const Fields& fields);

}  // namespace tracer
