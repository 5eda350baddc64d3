// The validator's builders: checked fields (checked_fields.h) -> the scene description.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include <glm/geometric.hpp>

#include "base/input_file.h"
#include "lang/internal/validator.h"
#include "scene/flat_shapes.h"
#include "scene/placement.h"

namespace tracer {
namespace {

namespace fs = std::filesystem;

// True if two edges are parallel, to within 1e-12 radians, and so span no area (computed on
// unit edges, so that neither tiny nor huge lengths underflow or overflow).
bool parallel(const dvec3& edge1, const dvec3& edge2) {
    return glm::length(glm::cross(normalized(edge1), normalized(edge2))) < 1e-12;
}

}  // namespace

// Scales a vector to unit length without overflow or underflow; zero stays zero.
dvec3 normalized(dvec3 v) {
    double largest = std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
    if (largest == 0 || !std::isfinite(largest)) return dvec3(0.0);
    return glm::normalize(v / largest);
}

void Validator::add_named_material(const Block& block) {
    kept_ = true;  // its name's span, for "unused" and "defined twice"
    auto [entry, inserted] = named_.try_emplace(block.name);
    if (!inserted) {
        Diagnostic* d = diagnostics_.error(file_, block.name_span, "material '" + block.name + "' is defined twice");
        Diagnostics::note(d, file_, entry->second.name_span, "the first definition is here");
        return;
    }
    entry->second.name_span = block.name_span;
    if (block.broken) return;  // already reported; keep the name so uses of it are not errors too
    Fields fields(*find_block_spec("material"));
    if (!check_body(block.body, *find_block_spec("material"), block.kind_span, fields)) return;
    entry->second.index = int(scene_.materials.size());
    scene_.materials.push_back(build_material(fields, block.name));
}

Material Validator::build_material(const Fields& fields, std::string name) {
    Material material;
    material.name = std::move(name);
    material.ka = fields.triple("ka");
    material.kd = fields.triple("kd");
    material.ks = fields.triple("ks");
    material.km = fields.triple("km");
    material.n = fields.number("n");
    material.kt = fields.triple("kt");
    material.ior = fields.number("ior");
    return material;
}

// The index of the shape's material: a named one, or its inline block added to the list (once
// for a material value that many shapes share: `let m = material { ... }`).
int Validator::material_index(const Fields& fields) {
    const PlainValue& value = fields.get("material");
    if (value.kind == PlainValue::Kind::Block) {
        if (auto shared = value_materials_.find(value.body.get()); shared != value_materials_.end())
            return shared->second.index;
        scene_.materials.push_back(build_material(fields.child("material"), ""));
        const int index = int(scene_.materials.size()) - 1;
        if (value.body.use_count() > 1) {
            value_materials_.emplace(value.body.get(), SharedMaterial{value.body, index});
            kept_ = true;
        }
        return index;
    }
    auto found = named_.find(value.text);
    if (found != named_.end()) return found->second.index;
    return kLaterMaterial - int(later_uses_.size() - 1);  // this block's use, just recorded by check_material_name
}

// A material used by name must be defined somewhere in the scene: marks it used, or records
// the use to be resolved once every block is in (it may be defined further down).
bool Validator::check_material_name(const PlainValue& value) {
    auto found = named_.find(value.text);
    if (found != named_.end()) {
        found->second.used = true;
        return true;
    }
    later_uses_.push_back({value.text, value.span});
    kept_ = true;
    return true;
}

void Validator::build(const Block& block, const Fields& fields) {
    const std::string_view kind = block.kind;  // compared length first
    if (block.group && (kind == "camera" || kind == "render"))
        return (void)diagnostics_.error(
            file_, block.kind_span, "a " + block.kind + " block is not placed by a group: write it outside the group");
    if (kind == "render") return build_render(block, fields);
    if (kind == "camera") return build_camera(block, fields);
    if (kind == "mesh") return build_mesh(block, fields);
    if (kind == "triangle" || kind == "quad" || kind == "box") return build_flat_shape(block, fields);
    if (kind == "light") {
        Placed group;
        if (!add_group_steps(block, group)) return;
        scene_.lights.push_back({Placement(group).point(fields.triple("position")), fields.triple("color")});
    } else if (kind == "sphere") {
        build_sphere(block, fields);
    } else if (kind == "plane") {
        build_plane(block, fields);
    } else if (kind == "cylinder" || kind == "cone") {
        build_cone(block, fields);
    } else if (kind == "disc") {
        build_disc(block, fields);
    }
}

void Validator::build_render(const Block& block, const Fields& fields) {
    RenderSettings& render = scene_.render;
    render.width = fields.integer("width");
    render.height = fields.integer("height");
    render.max_depth = fields.integer("max_depth");
    render.samples = fields.integer("samples");
    render.background = fields.triple("background");
    render.shadows = fields.boolean("shadows");
    render.transparent_shadows = fields.boolean("transparent_shadows");
    spawn_rules_from_name(fields.text("spawn_rules"), render.spawn_rules);  // checked by the table
    antialias_from_name(fields.text("antialias"), render.antialias);
    render.adaptive_threshold = fields.number("adaptive_threshold");
    render.adaptive_depth = fields.integer("adaptive_depth");
    render.adaptive_cell = fields.number("adaptive_cell");
    accelerator_from_name(fields.text("accel"), render.accel);
    render.leaf_size = fields.integer("leaf_size");

    if (const std::string problem = render_settings_problem(render); !problem.empty())
        diagnostics_.error(file_, block.kind_span, problem);
}

void Validator::build_camera(const Block& block, const Fields& fields) {
    Camera& camera = scene_.camera;
    camera.eye = fields.triple("eye");
    camera.lookat = fields.triple("lookat");
    camera.up = fields.triple("up");
    camera.fovy_degrees = fields.number("fovy");
    camera.focal = fields.number("focal");

    dvec3 forward = normalized(camera.lookat - camera.eye);
    if (forward == dvec3(0.0)) {
        diagnostics_.error(file_, fields.value_span("lookat"),
                           "'lookat' must differ from 'eye' (they set the viewing direction)");
        return;
    }
    if (glm::length(glm::cross(forward, normalized(camera.up))) < 1e-9) {
        Span at = fields.has("up") ? fields.value_span("up") : block.kind_span;
        diagnostics_.error(file_, at,
                           std::string("'up'") + (fields.has("up") ? "" : " (by default (0, 1, 0))") +
                               " is parallel to the viewing direction; choose an 'up' that is not");
    }
}

// The placement and material of a mesh or flat shape: its scale, rotate and translate keys, or
// the steps of its transform block (not both). False if the placement is refused.
bool Validator::build_placed(const Block& block, const Fields& fields, Placed& out) {
    out.line = Diagnostics::locate(file_, block.kind_span).line;
    out.material = material_index(fields);
    return build_placement(fields, out) && add_group_steps(block, out);
}

// The placement written by `fields`' scale, rotate and translate keys, or by the steps of its
// transform block (not both). False if it is refused (reported).
bool Validator::build_placement(const Fields& fields, Placed& out) {
    out.scale = fields.triple("scale");
    const Fields& rotate = fields.child("rotate");
    out.rotate_axis = normalized(rotate.triple("axis"));
    out.rotate_degrees = rotate.number("angle");
    out.translate = fields.triple("translate");
    if (!fields.has("transform")) return true;

    for (std::string_view own : {"scale", "rotate", "translate"}) {
        if (!fields.has(own)) continue;
        Diagnostic* d = diagnostics_.error(
            file_, fields.key_span("transform"),
            "'transform' cannot be combined with 'scale', 'rotate' or 'translate' in one block; write those "
            "steps inside the transform, in the order they apply");
        Diagnostics::note(d, file_, fields.key_span(own), "'" + std::string(own) + "' is set here");
        return false;
    }
    // The steps, and how much they scale in all (each factor is in range; their product must be too).
    double smallest = 1, largest = 1;
    for (const auto& step : fields.child("transform").steps()) {
        TransformStep out_step;
        if (step->has("scale")) {
            out_step.kind = TransformStep::Kind::Scale;
            out_step.vector = step->triple("scale");
            const dvec3 size = glm::abs(out_step.vector);
            smallest *= std::min({size.x, size.y, size.z});
            largest *= std::max({size.x, size.y, size.z});
        } else if (step->has("rotate")) {
            const Fields& turn = step->child("rotate");
            out_step.kind = TransformStep::Kind::Rotate;
            out_step.vector = normalized(turn.triple("axis"));
            out_step.degrees = turn.number("angle");
        } else {
            out_step.kind = TransformStep::Kind::Translate;
            out_step.vector = step->triple("translate");
        }
        out.steps.push_back(out_step);
    }
    if (smallest < kSmallestSize || largest > kLargestMagnitude) {
        char text[64];
        std::snprintf(text, sizeof text, "%.3g", smallest < kSmallestSize ? smallest : largest);
        diagnostics_.error(file_, fields.key_span("transform"),
                           std::string("the transform's scale steps multiply to ") + text +
                               " on some axis; sizes must stay between 1e-30 and 1e30");
        return false;
    }
    return true;
}

void Validator::build_mesh(const Block& block, const Fields& fields) {
    Mesh mesh;
    // Relative to the folder of the file the path is written in (the scene or an included file).
    fs::path path = fields.text("file");
    std::error_code ignored;
    if (path.is_relative())
        path = fs::absolute(fs::path(file_.file(fields.value_span("file")).path()), ignored).parent_path() / path;
    mesh.path = path.lexically_normal().string();
    mesh.named_at = Diagnostics::locate(file_, fields.value_span("file"));
    const std::string problem = input_file_problem(mesh.path, kMaxMeshFileBytes);  // looks, never opens
    if (!problem.empty())
        diagnostics_.error(file_, fields.value_span("file"), "cannot read mesh file '" + mesh.path + "': " + problem);
    mesh.flat = fields.text("shading") == "flat";
    if (build_placed(block, fields, mesh)) scene_.meshes.push_back(mesh);
}

// Placed, no corner of a flat shape may leave the renderer's range.
bool Validator::check_reach(const Block& block, const Placed& placed, const TriangleMesh& mesh) {
    const Placement placement(placed);
    double reach = 0;
    for (const dvec3& corner : mesh.positions) {
        const dvec3 p = glm::abs(placement.point(corner));
        reach = std::max({reach, p.x, p.y, p.z});
    }
    const std::string problem = placed_reach_problem(block.kind, reach);
    if (problem.empty()) return true;
    diagnostics_.error(file_, block.kind_span, problem);
    return false;
}

void Validator::build_flat_shape(const Block& block, const Fields& fields) {
    const std::string_view kind = block.kind;
    if (kind == "triangle") {
        FlatTriangle shape;
        shape.a = fields.triple("a");
        shape.b = fields.triple("b");
        shape.c = fields.triple("c");
        const dvec3 side1 = shape.b - shape.a, side2 = shape.c - shape.a;
        if (parallel(side1, side2))
            return (void)diagnostics_.error(file_, block.kind_span,
                                            "the triangle's corners lie on one line: it has no area");
        if (build_placed(block, fields, shape) && check_reach(block, shape, triangle_mesh(shape)))
            scene_.triangles.push_back(shape);
    } else if (kind == "quad") {
        Quad shape;
        shape.corner = fields.triple("corner"), shape.edge1 = fields.triple("edge1");
        shape.edge2 = fields.triple("edge2");
        if (parallel(shape.edge1, shape.edge2))
            return (void)diagnostics_.error(file_, fields.value_span("edge2"),
                                            "'edge2' is parallel to 'edge1': the quad has no area");
        if (build_placed(block, fields, shape) && check_reach(block, shape, triangle_mesh(shape)))
            scene_.quads.push_back(shape);
    } else {
        Box shape;
        shape.min = fields.triple("min"), shape.max = fields.triple("max");
        for (int axis = 0; axis < 3; ++axis) {
            if (shape.max[axis] > shape.min[axis]) continue;
            return (void)diagnostics_.error(file_, fields.value_span("max"),
                                            std::string("'max' must be greater than 'min' on every axis; on ") +
                                                "xyz"[axis] + ", " + format_number(shape.max[axis]) +
                                                " is not greater than " + format_number(shape.min[axis]));
        }
        if (build_placed(block, fields, shape) && check_reach(block, shape, triangle_mesh(shape)))
            scene_.boxes.push_back(shape);
    }
}

}  // namespace tracer
