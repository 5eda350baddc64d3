// The validator's builders: checked fields (checked_fields.h) -> the scene description.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include <glm/geometric.hpp>

#include "base/input_file.h"
#include "lang/internal/scene_assembly.h"
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

SceneAssembly::SceneAssembly(const Sources& sources, Diagnostics& reports, CheckPlacement check_placement)
    : file(sources), diagnostics(reports), check_group_placement(std::move(check_placement)) {
    std::error_code ignored;
    const fs::path scene_file(sources.scene().path());
    scene.source_path = fs::absolute(scene_file, ignored).lexically_normal().string();
}

Material build_material(SceneAssembly& a, const Fields& fields, std::string name) {
    Material material;
    material.name = std::move(name);
    const Paint ka = build_paint(a, fields, "ka"), kd = build_paint(a, fields, "kd");
    material.ka = ka.color, material.ka_pattern = ka.pattern;
    material.kd = kd.color, material.kd_pattern = kd.pattern;
    material.ks = fields.triple("ks");
    material.km = fields.triple("km");
    material.n = fields.number("n");
    material.kt = fields.triple("kt");
    material.ior = fields.number("ior");
    return material;
}

// The index of the shape's material: a named one, or its inline block added to the list (once
// for a material value that many shapes share: `let m = material { ... }`).
int material_index(SceneAssembly& a, const Fields& fields) {
    const PlainValue& value = fields.get("material");
    if (value.kind == PlainValue::Kind::Block) {
        if (auto shared = a.value_materials.find(value.body.get()); shared != a.value_materials.end())
            return shared->second.index;
        Material material = build_material(a, fields.child("material"), "");
        a.scene.materials.push_back(std::move(material));
        const int index = int(a.scene.materials.size()) - 1;
        if (value.body.use_count() > 1) {
            a.value_materials.emplace(value.body.get(), SceneAssembly::SharedMaterial{value.body, index});
            a.kept = true;
        }
        return index;
    }
    if (auto found = a.material_by_name.find(value.text); found != a.material_by_name.end()) return found->second;
    a.later_materials.push_back(value.text);
    return SceneAssembly::kLaterMaterial - int(a.later_materials.size() - 1);
}

void add_light(SceneAssembly& a, const Block& block, const Light& light) {
    const long long before = a.light_samples;
    a.light_samples += light.samples();
    if (a.light_samples > kMostLightSamples) {
        if (before > kMostLightSamples) return;  // reported at the first light past the bound
        a.diagnostics.error(a.file, block.kind_span,
                            "the scene's lights have " + std::to_string(a.light_samples) +
                                " samples with this one, more than " + std::to_string(kMostLightSamples) +
                                ": every point shaded would trace a shadow ray to each (fewer samples or lights)");
        return;
    }
    a.scene.lights.push_back(light);
}

// Fading with distance (fade_distance 0: none), as the block says.
static void read_fading(const Fields& fields, Light& light) {
    light.fade_distance = fields.number("fade_distance");
    light.fade_power = fields.number("fade_power");
}

void build_light(SceneAssembly& a, const Block& block, const Fields& fields) {
    Placed group;
    if (!add_group_steps(a, block, group)) return;
    Light light{Placement(group).point(fields.triple("position")), fields.triple("color")};
    read_fading(fields, light);
    add_light(a, block, light);
}

// `v` scaled to unit length into `out`; false, reporting `problem` at `key`'s value, if it has
// no length (or one that is not finite).
static bool unit_direction(SceneAssembly& a, const Fields& fields, std::string_view key, const dvec3& v,
                           const std::string& problem, dvec3& out) {
    const double length = glm::length(v);
    if (!(length > 0) || !std::isfinite(length)) {
        a.diagnostics.error(a.file, fields.value_span(key), problem);
        return false;
    }
    out = v / length;
    return true;
}

// A spotlight: its position and the point it aims at placed by the groups around it.
static void build_spotlight(SceneAssembly& a, const Block& block, const Fields& fields) {
    Placed group;
    if (!add_group_steps(a, block, group)) return;
    const Placement placement(group);
    Light light{placement.point(fields.triple("position")), fields.triple("color")};
    light.kind = Light::Kind::Spot;
    if (!unit_direction(a, fields, "point_at", placement.point(fields.triple("point_at")) - light.position,
                        "a spotlight must point away from its position: point_at is the position itself",
                        light.direction))
        return;
    light.radius = fields.number("radius");
    light.falloff = fields.number("falloff");
    light.tightness = fields.number("tightness");
    if (light.falloff < light.radius) {
        a.diagnostics.error(a.file, fields.value_span("falloff"),
                            "a spotlight's falloff (" + format_number(light.falloff) +
                                " degrees) must be at least its radius (" + format_number(light.radius) +
                                "): its light fades from the radius out to the falloff");
        return;
    }
    read_fading(fields, light);
    add_light(a, block, light);
}

// A parallel light: its direction turned by the groups around it.
static void build_parallel_light(SceneAssembly& a, const Block& block, const Fields& fields) {
    Placed group;
    if (!add_group_steps(a, block, group)) return;
    Light light;
    light.kind = Light::Kind::Parallel;
    light.color = fields.triple("color");
    if (!unit_direction(a, fields, "direction", Placement(group).linear * fields.triple("direction"),
                        "a parallel light's direction has no length once placed by its groups", light.direction))
        return;
    add_light(a, block, light);
}

// False (reported) unless a sphere light's edges have one length and its counts are equal
// (POV-Ray's orient asks the same): its disc turns to face each point.
static bool sphere_light_is_round(SceneAssembly& a, const Fields& fields, const Light& light) {
    const double l1 = glm::length(light.edge1), l2 = glm::length(light.edge2);
    if (!(std::abs(l1 - l2) <= 1e-9 * std::max(l1, l2))) {
        a.diagnostics.error(a.file, fields.value_span("edge2"),
                            "a sphere light's edges must be of one length, its diameter: edge1 is " +
                                format_number(l1) + " long, edge2 " + format_number(l2) + " (once placed)");
        return false;
    }
    if (light.samples1 != light.samples2) {
        a.diagnostics.error(a.file, fields.value_span("samples2"),
                            "a sphere light needs as many samples along each edge: samples1 is " +
                                std::to_string(light.samples1) + ", samples2 " + std::to_string(light.samples2));
        return false;
    }
    return true;
}

// An area light: its centre and edges placed by the groups around it.
void build_area_light(SceneAssembly& a, const Block& block, const Fields& fields) {
    Placed group;
    if (!add_group_steps(a, block, group)) return;
    const Placement placement(group);
    Light light{placement.point(fields.triple("position")), fields.triple("color")};
    light.edge1 = placement.linear * fields.triple("edge1");
    light.edge2 = placement.linear * fields.triple("edge2");
    light.samples1 = int(fields.number("samples1"));
    light.samples2 = int(fields.number("samples2"));
    light.jitter = fields.boolean("jitter");
    light.adaptive = fields.boolean("adaptive");
    const std::string shape = fields.text("shape");
    light.shape = shape == "disc"     ? Light::Shape::Disc
                  : shape == "sphere" ? Light::Shape::Sphere
                                      : Light::Shape::Rectangle;
    const dvec3 across = glm::cross(light.edge1, light.edge2);
    if (!(glm::dot(across, across) > 0)) {
        a.diagnostics.error(a.file, fields.value_span("edge2"),
                            "an area light's edges must span a rectangle: edge2 is parallel to edge1");
        return;
    }
    if (light.shape == Light::Shape::Sphere && !sphere_light_is_round(a, fields, light)) return;
    read_fading(fields, light);
    add_light(a, block, light);
}

// A named material: the next of the scene's materials.
static void build_named_material(SceneAssembly& a, const Block& block, const Fields& fields) {
    a.material_by_name[block.name] = int(a.scene.materials.size());
    Material material = build_material(a, fields, block.name);
    a.scene.materials.push_back(std::move(material));
}

// The builder of each kind of block.
struct Builder {
    std::string_view kind;
    void (*build)(SceneAssembly& a, const Block& block, const Fields& fields);
};
constexpr Builder kBuilders[] = {
    {"material", build_named_material},
    {"render", build_render},
    {"camera", build_camera},
    {"light", build_light},
    {"area_light", build_area_light},
    {"spotlight", build_spotlight},
    {"parallel_light", build_parallel_light},
    {"sphere", build_sphere},
    {"plane", build_plane},
    {"cylinder", build_cone},
    {"cone", build_cone},
    {"disc", build_disc},
    {"mesh", build_mesh},
    {"triangle", build_flat_shape},
    {"quad", build_flat_shape},
    {"box", build_flat_shape},
};

void build_block(SceneAssembly& a, const Block& block, const Fields& fields) {
    if (block.group && !check_solid_part(a, block)) return;
    for (const Builder& builder : kBuilders)
        if (builder.kind == block.kind) return builder.build(a, block, fields);
}

void build_render(SceneAssembly& a, const Block& block, const Fields& fields) {
    RenderSettings& render = a.scene.render;
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
    encoding_from_name(fields.text("encoding"), render.encoding);

    if (const std::string problem = render_settings_problem(render); !problem.empty())
        a.diagnostics.error(a.file, block.kind_span, problem);
}

void build_camera(SceneAssembly& a, const Block& block, const Fields& fields) {
    Camera& camera = a.scene.camera;
    camera.eye = fields.triple("eye");
    camera.lookat = fields.triple("lookat");
    camera.up = fields.triple("up");
    camera.fovy_degrees = fields.number("fovy");
    camera.focal = fields.number("focal");

    dvec3 forward = normalized(camera.lookat - camera.eye);
    if (forward == dvec3(0.0)) {
        a.diagnostics.error(a.file, fields.value_span("lookat"),
                            "'lookat' must differ from 'eye' (they set the viewing direction)");
        return;
    }
    if (glm::length(glm::cross(forward, normalized(camera.up))) < 1e-9) {
        Span at = fields.has("up") ? fields.value_span("up") : block.kind_span;
        a.diagnostics.error(a.file, at,
                            std::string("'up'") + (fields.has("up") ? "" : " (by default (0, 1, 0))") +
                                " is parallel to the viewing direction; choose an 'up' that is not");
    }
}

// The placement and material of a mesh or flat shape: its steps in the order written, then its
// groups'. False if the placement is refused.
bool build_placed(SceneAssembly& a, const Block& block, const Fields& fields, Placed& out) {
    out.line = Diagnostics::locate(a.file, block.kind_span).line;
    out.material = material_index(a, fields);
    return build_placement(a, fields, out) && add_group_steps(a, block, out) && check_placed_scale(a, block, out);
}

// The placement written by `fields`' steps (scale, rotate, translate, transform) in the order
// written, a transform's steps at its place. Scale, rotate, translate, one each in that order
// (the order they always had), are kept as Placed's three fields: the same arithmetic as steps,
// and the same scene description as before. False if it is refused (reported).
bool build_placement(SceneAssembly& a, const Fields& fields, Placed& out) {
    // Step 1: the chain as written, each step with the span of the key that wrote it.
    std::vector<std::pair<const Fields*, Span>> chain;
    bool in_plain_order = true;
    int last_plain = -1;  // 0 scale, 1 rotate, 2 translate: the last one seen
    for (const auto& step : fields.steps()) {
        const Span written = step->key_span(step->has("transform") ? "transform"
                                            : step->has("scale")   ? "scale"
                                            : step->has("rotate")  ? "rotate"
                                                                   : "translate");
        if (step->has("transform")) {
            in_plain_order = false;
            for (const auto& inner : step->child("transform").steps()) chain.emplace_back(inner.get(), written);
            continue;
        }
        const int plain = step->has("scale") ? 0 : step->has("rotate") ? 1 : 2;
        in_plain_order = in_plain_order && plain > last_plain;
        last_plain = plain;
        chain.emplace_back(step.get(), written);
    }
    // Step 2: the steps, and how much they scale in all (each factor is in range; their product
    // must be too).
    double smallest = 1, largest = 1;
    for (const auto& [step, written] : chain) {
        TransformStep out_step;
        if (step->has("scale")) {
            out_step.kind = TransformStep::Kind::Scale;
            out_step.vector = step->triple("scale");
            const dvec3 size = glm::abs(out_step.vector);
            smallest *= std::min({size.x, size.y, size.z});
            largest *= std::max({size.x, size.y, size.z});
            if (smallest < kSmallestSize || largest > kLargestMagnitude) {
                char text[64];
                std::snprintf(text, sizeof text, "%.3g", smallest < kSmallestSize ? smallest : largest);
                a.diagnostics.error(a.file, written,
                                    std::string("the scale steps up to here multiply to ") + text +
                                        " on some axis; sizes must stay between 1e-30 and 1e30");
                return false;
            }
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
    // Step 3: the plain order, as the three fields.
    if (in_plain_order) {
        for (const TransformStep& step : out.steps) {
            if (step.kind == TransformStep::Kind::Scale) out.scale = step.vector;
            if (step.kind == TransformStep::Kind::Rotate) {
                out.rotate_axis = step.vector;
                out.rotate_degrees = step.degrees;
            }
            if (step.kind == TransformStep::Kind::Translate) out.translate = step.vector;
        }
        out.steps.clear();
    }
    return true;
}

void build_mesh(SceneAssembly& a, const Block& block, const Fields& fields) {
    Mesh mesh;
    // Relative to the folder of the file the path is written in (the scene or an included file).
    fs::path path = fields.text("file");
    std::error_code ignored;
    if (path.is_relative())
        path = fs::absolute(fs::path(a.file.file(fields.value_span("file")).path()), ignored).parent_path() / path;
    mesh.path = path.lexically_normal().string();
    mesh.named_at = Diagnostics::locate(a.file, fields.value_span("file"));
    const std::string problem = input_file_problem(mesh.path, kMaxMeshFileBytes);  // looks, never opens
    if (!problem.empty())
        a.diagnostics.error(a.file, fields.value_span("file"), "cannot read mesh file '" + mesh.path + "': " + problem);
    mesh.flat = fields.text("shading") == "flat";
    if (!build_placed(a, block, fields, mesh)) return;
    const int solid = block.group ? solid_of(a, block) : kNoSolid;
    place_material(a, solid == kNoSolid ? ShapeList::Meshes : ShapeList::SolidMeshes, mesh.material, Placement(mesh));
    if (solid == kNoSolid) return a.scene.meshes.push_back(mesh);
    add_solid_part(a, solid, SolidPart::Kind::Mesh, a.scene.solid_meshes.size());
    a.scene.solid_meshes.push_back(mesh);
}

// Placed, no corner of a flat shape may leave the renderer's range.
bool check_reach(SceneAssembly& a, const Block& block, const Placed& placed, const TriangleMesh& mesh) {
    const Placement placement(placed);
    double reach = 0;
    for (const dvec3& corner : mesh.positions) {
        const dvec3 p = glm::abs(placement.point(corner));
        reach = std::max({reach, p.x, p.y, p.z});
    }
    const std::string problem = placed_reach_problem(block.kind, reach);
    if (problem.empty()) return true;
    a.diagnostics.error(a.file, block.kind_span, problem);
    return false;
}

void build_flat_shape(SceneAssembly& a, const Block& block, const Fields& fields) {
    const std::string_view kind = block.kind;
    if (kind == "triangle") {
        FlatTriangle shape;
        shape.a = fields.triple("a");
        shape.b = fields.triple("b");
        shape.c = fields.triple("c");
        const dvec3 side1 = shape.b - shape.a, side2 = shape.c - shape.a;
        if (parallel(side1, side2))
            return (void)a.diagnostics.error(a.file, block.kind_span,
                                             "the triangle's corners lie on one line: it has no area");
        if (!build_placed(a, block, fields, shape) || !check_reach(a, block, shape, triangle_mesh(shape))) return;
        place_material(a, ShapeList::Triangles, shape.material, Placement(shape));
        a.scene.triangles.push_back(shape);
    } else if (kind == "quad") {
        Quad shape;
        shape.corner = fields.triple("corner"), shape.edge1 = fields.triple("edge1");
        shape.edge2 = fields.triple("edge2");
        if (parallel(shape.edge1, shape.edge2))
            return (void)a.diagnostics.error(a.file, fields.value_span("edge2"),
                                             "'edge2' is parallel to 'edge1': the quad has no area");
        if (!build_placed(a, block, fields, shape) || !check_reach(a, block, shape, triangle_mesh(shape))) return;
        place_material(a, ShapeList::Quads, shape.material, Placement(shape));
        a.scene.quads.push_back(shape);
    } else {
        Box shape;
        shape.min = fields.triple("min"), shape.max = fields.triple("max");
        for (int axis = 0; axis < 3; ++axis) {
            if (shape.max[axis] > shape.min[axis]) continue;
            return (void)a.diagnostics.error(a.file, fields.value_span("max"),
                                             std::string("'max' must be greater than 'min' on every axis; on ") +
                                                 "xyz"[axis] + ", " + format_number(shape.max[axis]) +
                                                 " is not greater than " + format_number(shape.min[axis]));
        }
        if (!build_placed(a, block, fields, shape) || !check_reach(a, block, shape, triangle_mesh(shape))) return;
        const int solid = block.group ? solid_of(a, block) : kNoSolid;
        place_material(a, solid == kNoSolid ? ShapeList::Boxes : ShapeList::SolidBoxes, shape.material,
                       Placement(shape));
        if (solid == kNoSolid) return a.scene.boxes.push_back(shape);
        add_solid_part(a, solid, SolidPart::Kind::Box, a.scene.solid_boxes.size());
        a.scene.solid_boxes.push_back(shape);
    }
}

void set_parameters(SceneAssembly& a, const std::vector<std::pair<std::string, PlainValue>>& parameters) {
    for (const auto& [name, value] : parameters)
        a.scene.parameters.push_back(
            {name, value.kind == PlainValue::Kind::Vector ? value.components : std::vector<double>{value.number},
             value.kind == PlainValue::Kind::Vector});
}

void resolve_later_materials(SceneAssembly& a) {
    auto resolve = [&](auto& shapes) {
        for (auto& shape : shapes)
            if (shape.material <= SceneAssembly::kLaterMaterial) {
                const std::string& name = a.later_materials[size_t(SceneAssembly::kLaterMaterial - shape.material)];
                auto found = a.material_by_name.find(name);
                shape.material = found != a.material_by_name.end() ? found->second : -1;
            }
    };
    SceneDescription& scene = a.scene;
    resolve(scene.spheres), resolve(scene.planes), resolve(scene.meshes);
    resolve(scene.triangles), resolve(scene.quads), resolve(scene.boxes);
    resolve(scene.cones), resolve(scene.discs);
    resolve(scene.solid_spheres), resolve(scene.solid_boxes), resolve(scene.solid_cones), resolve(scene.half_spaces);
    resolve(scene.solid_meshes);
}

// Warnings where the image cannot be what the author meant (the scene stays valid): nothing to
// see, or surfaces that would reflect light with no light to reflect.
void warn_about_the_picture(const SceneAssembly& a) {
    const SceneDescription& scene = a.scene;
    const Location whole = Diagnostics::whole_file(a.file.scene().path());
    const bool flat_shapes = !scene.triangles.empty() || !scene.quads.empty() || !scene.boxes.empty() ||
                             !scene.cones.empty() || !scene.discs.empty() || !scene.solids.empty();
    if (scene.spheres.empty() && scene.planes.empty() && scene.meshes.empty() && !flat_shapes) {
        a.diagnostics.report(Severity::Warning, whole,
                             "the scene has no shapes: the image will be the background colour only");
        return;
    }
    // Spheres alone, each wholly behind the eye: nothing in front of it.
    const dvec3 forward = glm::normalize(scene.camera.lookat - scene.camera.eye);
    const bool all_behind = scene.planes.empty() && scene.meshes.empty() && !flat_shapes &&
                            std::all_of(scene.spheres.begin(), scene.spheres.end(), [&](const Sphere& sphere) {
                                return glm::dot(sphere.center - scene.camera.eye, forward) < -sphere.radius;
                            });
    if (all_behind)
        a.diagnostics.report(Severity::Warning, whole,
                             "every shape is behind the camera: the image will be the background colour only");
    auto needs_light = [&](const auto& shapes) {
        return std::any_of(shapes.begin(), shapes.end(), [&](const auto& shape) {
            const Material& material = scene.materials[size_t(shape.material)];
            return material.kd != dvec3(0.0) || material.ks != dvec3(0.0);
        });
    };
    if (scene.lights.empty() &&
        (needs_light(scene.spheres) || needs_light(scene.planes) || needs_light(scene.meshes) ||
         needs_light(scene.triangles) || needs_light(scene.quads) || needs_light(scene.boxes) ||
         needs_light(scene.cones) || needs_light(scene.discs) || needs_light(scene.solid_spheres) ||
         needs_light(scene.solid_boxes) || needs_light(scene.solid_cones) || needs_light(scene.half_spaces) ||
         needs_light(scene.solid_meshes)))
        a.diagnostics.report(Severity::Warning, whole,
                             "the scene has no light: its diffuse and specular colours (kd, ks) will not show, only "
                             "ka; add one, e.g. light { position (0, 5, 5) }");
}

}  // namespace tracer
