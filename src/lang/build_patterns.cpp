// Patterns (scene/pattern.h): checked pattern fields -> SceneDescription::patterns and images,
// and the placed copies of patterned materials that let patterns move with their shapes.
#include <filesystem>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "base/input_file.h"
#include "lang/internal/scene_assembly.h"
#include "lang/schema.h"
#include "scene/pattern.h"

namespace tracer {
namespace {

namespace fs = std::filesystem;

// `placement`'s inverse: world (or the outer space) -> own coordinates.
Affine inverse_of(const Placement& placement) {
    Affine inverse;
    inverse.linear = glm::inverse(placement.linear);
    inverse.offset = -(inverse.linear * placement.translate);
    return inverse;
}

std::vector<ColorStop> color_map(const PlainValue& list) {
    std::vector<ColorStop> stops;
    stops.reserve(list.items.size());
    for (const PlainValue& stop : list.items) {
        const PlainValue& colour = stop.items[1];
        stops.push_back(
            {stop.items[0].number, colour.kind == PlainValue::Kind::Number
                                       ? dvec3(colour.number)
                                       : dvec3(colour.components[0], colour.components[1], colour.components[2])});
    }
    return stops;
}

// The image file of an image pattern: its absolute path, checked (never opened) here; its texels
// are read with the scene's other files (io/texture_file.h).
int add_image(SceneAssembly& a, const Fields& fields) {
    fs::path path = fields.text("file");
    std::error_code ignored;
    if (path.is_relative())
        path = fs::absolute(fs::path(a.file.file(fields.value_span("file")).path()), ignored).parent_path() / path;
    ImageFile image;
    image.path = path.lexically_normal().string();
    image.named_at = Diagnostics::locate(a.file, fields.value_span("file"));
    const std::string problem = input_file_problem(image.path, kMaxImageFileBytes);
    if (!problem.empty())
        a.diagnostics.error(a.file, fields.value_span("file"),
                            "cannot read image file '" + image.path + "': " + problem);
    for (size_t i = 0; i < a.scene.images.size(); ++i)  // each file read once
        if (a.scene.images[i].path == image.path) return int(i);
    a.scene.images.push_back(std::move(image));
    return int(a.scene.images.size()) - 1;
}

int build_pattern(SceneAssembly& a, const Fields& fields) {
    const BlockSpec& spec = fields.spec();
    Pattern pattern;
    pattern_kind_from_name(spec.kind, pattern.kind);  // checked by the table
    mapping_from_name(fields.text("mapping"), pattern.mapping);
    Placed placed;
    if (build_placement(a, fields, placed)) pattern.to_pattern = inverse_of(Placement(placed));
    auto has = [&spec](std::string_view key) { return spec.find_key(key) != nullptr; };
    if (has("even")) pattern.even = build_paint(a, fields, "even");
    if (has("odd")) pattern.odd = build_paint(a, fields, "odd");
    if (has("colors")) pattern.colors = color_map(fields.get("colors"));
    if (has("axis")) pattern.axis = normalized(fields.triple("axis"));
    if (has("turbulence")) pattern.turbulence = fields.number("turbulence");
    if (has("octaves")) pattern.octaves = fields.integer("octaves");
    if (has("file")) pattern.image = add_image(a, fields);
    if (has("wrap")) wrap_from_name(fields.text("wrap"), pattern.wrap);
    pattern.multiply = fields.triple("multiply");
    a.scene.patterns.push_back(std::move(pattern));
    return int(a.scene.patterns.size()) - 1;
}

// A placement's numbers, as a key for the copies of a material.
std::vector<double> numbers_of(const Affine& map) {
    std::vector<double> numbers;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) numbers.push_back(map.linear[c][r]);
    for (int r = 0; r < 3; ++r) numbers.push_back(map.offset[r]);
    return numbers;
}

// The copy of patterned `material` for shapes whose own coordinates are `to_object` of the world's.
int placed_copy(SceneAssembly& a, int material, const Affine& to_object) {
    auto [found, is_new] = a.placed_materials.try_emplace({material, numbers_of(to_object)}, 0);
    if (!is_new) return found->second;
    Material copy = a.scene.materials[size_t(material)];
    copy.to_object = to_object;
    a.scene.materials.push_back(std::move(copy));
    found->second = int(a.scene.materials.size()) - 1;
    return found->second;
}

int& material_of(SceneDescription& scene, ShapeList list, size_t index) {
    switch (list) {
        case ShapeList::Spheres: return scene.spheres[index].material;
        case ShapeList::Planes: return scene.planes[index].material;
        case ShapeList::Meshes: return scene.meshes[index].material;
        case ShapeList::Triangles: return scene.triangles[index].material;
        case ShapeList::Quads: return scene.quads[index].material;
        case ShapeList::Boxes: return scene.boxes[index].material;
        case ShapeList::Cones: return scene.cones[index].material;
        case ShapeList::Discs: return scene.discs[index].material;
        case ShapeList::SolidSpheres: return scene.solid_spheres[index].material;
        case ShapeList::SolidBoxes: return scene.solid_boxes[index].material;
        case ShapeList::SolidCones: return scene.solid_cones[index].material;
        case ShapeList::HalfSpaces: return scene.half_spaces[index].material;
        case ShapeList::SolidMeshes: return scene.solid_meshes[index].material;
    }
    return scene.spheres[index].material;
}

size_t size_of(const SceneDescription& scene, ShapeList list) {
    switch (list) {
        case ShapeList::Spheres: return scene.spheres.size();
        case ShapeList::Planes: return scene.planes.size();
        case ShapeList::Meshes: return scene.meshes.size();
        case ShapeList::Triangles: return scene.triangles.size();
        case ShapeList::Quads: return scene.quads.size();
        case ShapeList::Boxes: return scene.boxes.size();
        case ShapeList::Cones: return scene.cones.size();
        case ShapeList::Discs: return scene.discs.size();
        case ShapeList::SolidSpheres: return scene.solid_spheres.size();
        case ShapeList::SolidBoxes: return scene.solid_boxes.size();
        case ShapeList::SolidCones: return scene.solid_cones.size();
        case ShapeList::HalfSpaces: return scene.half_spaces.size();
        case ShapeList::SolidMeshes: return scene.solid_meshes.size();
    }
    return 0;
}

}  // namespace

Paint build_paint(SceneAssembly& a, const Fields& fields, std::string_view key) {
    const PlainValue& value = fields.get(key);
    if (value.kind != PlainValue::Kind::Block) return {fields.triple(key), -1};
    if (auto shared = a.value_patterns.find(value.body.get()); shared != a.value_patterns.end())
        return {dvec3(0.0), shared->second.second};
    const int index = build_pattern(a, fields.child(key));
    if (value.body.use_count() > 1) {
        a.value_patterns.emplace(value.body.get(), std::pair{value.body, index});
        a.kept = true;
    }
    return {dvec3(0.0), index};
}

void place_material(SceneAssembly& a, ShapeList list, int& material, const Placement& placement) {
    if (placement.linear == glm::dmat3(1.0) && placement.translate == dvec3(0.0)) return;
    if (material <= SceneAssembly::kLaterMaterial) {
        a.later_placements.push_back({list, size_of(a.scene, list), inverse_of(placement)});
        return;
    }
    if (material >= 0 && a.scene.materials[size_t(material)].patterned())
        material = placed_copy(a, material, inverse_of(placement));
}

void place_later_materials(SceneAssembly& a) {
    for (const SceneAssembly::LaterPlacement& later : a.later_placements) {
        int& material = material_of(a.scene, later.list, later.index);
        if (material >= 0 && a.scene.materials[size_t(material)].patterned())
            material = placed_copy(a, material, later.to_object);
    }
}

}  // namespace tracer
