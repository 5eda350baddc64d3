#include "scene/scene_json.h"

#include <algorithm>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "scene/mesh_facts.h"

namespace tracer {
namespace {

using Json = nlohmann::ordered_json;

Json vec(const dvec3& v) {
    return Json::array({v.x, v.y, v.z});
}

// `second` after `first`.
Affine then(const Affine& first, const Affine& second) {
    return {second.linear * first.linear, second.linear * first.offset + second.offset};
}

// An affine map as three rows of four numbers.
Json affine_json(const Affine& map) {
    Json rows = Json::array();
    for (int r = 0; r < 3; ++r)
        rows.push_back(Json::array({map.linear[0][r], map.linear[1][r], map.linear[2][r], map.offset[r]}));
    return rows;
}

// A pattern with its whole placement: `to_pattern` maps world points (uv mapping: (u, v, 0))
// into its space, through the shape's, the outer patterns' and its own steps.
Json pattern_json(const SceneDescription& scene, int index, const Affine& to_outer, const Affine& uv_to_outer);

Json paint_json(const SceneDescription& scene, const dvec3& color, int pattern, const Affine& to_outer,
                const Affine& uv_to_outer) {
    return pattern >= 0 ? pattern_json(scene, pattern, to_outer, uv_to_outer) : vec(color);
}

Json pattern_json(const SceneDescription& scene, int index, const Affine& to_outer, const Affine& uv_to_outer) {
    const Pattern& p = scene.patterns.at(size_t(index));
    const Affine to_own = then(to_outer, p.to_pattern), uv_to_own = then(uv_to_outer, p.to_pattern);
    Json out{{"pattern", pattern_kind_name(p.kind)},
             {"mapping", mapping_name(p.mapping)},
             {"to_pattern", affine_json(p.mapping == Mapping::Uv ? uv_to_own : to_own)}};
    if (p.multiply != dvec3(1.0)) out["multiply"] = vec(p.multiply);
    switch (p.kind) {
        case PatternKind::Checker:
            out["even"] = paint_json(scene, p.even.color, p.even.pattern, to_own, uv_to_own);
            out["odd"] = paint_json(scene, p.odd.color, p.odd.pattern, to_own, uv_to_own);
            break;
        case PatternKind::Image:
            out["file"] = scene.images.at(size_t(p.image)).path;
            out["wrap"] = wrap_name(p.wrap);
            break;
        default:
            out["colors"] = Json::array();
            for (const ColorStop& stop : p.colors) out["colors"].push_back(Json::array({stop.at, vec(stop.color)}));
            out["axis"] = vec(p.axis);
            out["turbulence"] = p.turbulence;
            out["octaves"] = p.octaves;
    }
    return out;
}

Json material_json(const SceneDescription& scene, int index) {
    const Material& m = scene.materials.at(size_t(index));
    Json out{{"name", m.name},
             {"ka", paint_json(scene, m.ka, m.ka_pattern, m.to_object, Affine{})},
             {"kd", paint_json(scene, m.kd, m.kd_pattern, m.to_object, Affine{})},
             {"ks", vec(m.ks)},
             {"km", vec(m.km)},
             {"n", m.n},
             {"kt", vec(m.kt)},
             {"ior", m.ior}};
    // Where the shape's own coordinates are (its surface's (u, v) are measured there).
    if (m.patterned() && !(m.to_object == Affine{})) out["to_object"] = affine_json(m.to_object);
    return out;
}

// Where a shape is placed: its scale, rotate and translate, or (with steps after them, its
// groups' or its own) all of it as steps, the three first where they do anything.
void add_placement(Json& out, const Placed& placed) {
    if (placed.steps.empty()) {
        out["scale"] = vec(placed.scale);
        out["rotate"] = {{"axis", vec(placed.rotate_axis)}, {"angle", placed.rotate_degrees}};
        out["translate"] = vec(placed.translate);
        return;
    }
    out["transform"] = Json::array();
    for (const TransformStep& step : placement_steps(placed)) {
        if (step.kind == TransformStep::Kind::Scale) out["transform"].push_back({{"scale", vec(step.vector)}});
        if (step.kind == TransformStep::Kind::Rotate)
            out["transform"].push_back({{"rotate", {{"axis", vec(step.vector)}, {"angle", step.degrees}}}});
        if (step.kind == TransformStep::Kind::Translate) out["transform"].push_back({{"translate", vec(step.vector)}});
    }
}

// A placed shape's entry: its own keys, its placement, its material.
Json placed_json(const SceneDescription& scene, const Placed& placed, Json own) {
    add_placement(own, placed);
    own["material"] = material_json(scene, placed.material);
    return own;
}

// The shapes that may be parts of solids, as entries of their arrays.
Json sphere_json(const SceneDescription& scene, const Sphere& s) {
    return {{"center", vec(s.center)}, {"radius", s.radius}, {"material", material_json(scene, s.material)}};
}
Json plane_json(const SceneDescription& scene, const Plane& p) {
    return {{"point", vec(p.point)}, {"normal", vec(p.normal)}, {"material", material_json(scene, p.material)}};
}
Json box_json(const SceneDescription& scene, const Box& b) {
    return placed_json(scene, b, {{"min", vec(b.min)}, {"max", vec(b.max)}});
}
Json cone_json(const SceneDescription& scene, const Cone& cone) {
    return {{"base", vec(cone.base)},        {"top", vec(cone.top)}, {"base_radius", cone.base_radius},
            {"top_radius", cone.top_radius}, {"caps", cone.caps},    {"material", material_json(scene, cone.material)}};
}

// A solid: its operation and its parts in order, each a shape (its kind a key: sphere, box,
// cone, half_space, mesh) or the index of another solid of the array (nested: not an object by itself).
Json solid_json(const SceneDescription& scene, const Solid& solid) {
    static constexpr const char* kOps[] = {"union", "intersection", "difference"};
    Json parts = Json::array();
    for (const SolidPart& part : solid.parts) {
        switch (part.kind) {
            case SolidPart::Kind::Sphere:
                parts.push_back({{"kind", "sphere"}, {"sphere", sphere_json(scene, scene.solid_spheres[part.index])}});
                break;
            case SolidPart::Kind::Box:
                parts.push_back({{"kind", "box"}, {"box", box_json(scene, scene.solid_boxes[part.index])}});
                break;
            case SolidPart::Kind::Cone:
                parts.push_back({{"kind", "cone"}, {"cone", cone_json(scene, scene.solid_cones[part.index])}});
                break;
            case SolidPart::Kind::HalfSpace:
                parts.push_back(
                    {{"kind", "half_space"}, {"half_space", plane_json(scene, scene.half_spaces[part.index])}});
                break;
            case SolidPart::Kind::Mesh: {
                const Mesh& m = scene.solid_meshes[part.index];
                Json entry = placed_json(scene, m, {{"file", m.path}});
                if (m.flat) entry["shading"] = "flat";
                parts.push_back({{"kind", "mesh"}, {"mesh", std::move(entry)}});
                break;
            }
            case SolidPart::Kind::Solid: parts.push_back({{"kind", "solid"}, {"solid", part.index}}); break;
        }
    }
    return {{"op", kOps[int(solid.op)]}, {"nested", solid.nested}, {"parts", std::move(parts)}};
}

// The scene's big arrays (one entry per shape), made entry by entry: all at once into the
// document, or, when `later` is given, left as a placeholder string and written afterwards.
struct LaterArray {
    std::string key;
    size_t count;
    std::function<Json(size_t)> entry;
};

void add_array(Json& out, const char* key, size_t count, std::function<Json(size_t)> entry,
               std::vector<LaterArray>* later) {
    if (later) {
        out[key] = std::string(
                       "\x01"
                       "array:") +
                   key;
        later->push_back({key, count, std::move(entry)});
        return;
    }
    out[key] = Json::array();
    for (size_t i = 0; i < count; ++i) out[key].push_back(entry(i));
}

// The same, an entry per item of `items` (kept by reference: the caller's must outlive `later`).
template <typename Item, typename Entry>
void add_array(Json& out, const char* key, const std::vector<Item>& items, Entry entry,
               std::vector<LaterArray>* later) {
    add_array(
        out, key, items.size(), [&items, entry](size_t i) -> Json { return entry(items[i]); }, later);
}

// As tracer --dump-json has always printed it: keys sorted (nlohmann::json), indent 2.
std::string text_of(const Json& value) {
    return nlohmann::json(value).dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
}

// The render block's settings.
Json render_json(const RenderSettings& r) {
    Json out = {{"width", r.width},
                {"height", r.height},
                {"max_depth", r.max_depth},
                {"samples", r.samples},
                {"background", vec(r.background)},
                {"shadows", r.shadows},
                {"accel", accelerator_name(r.accel)},
                {"leaf_size", r.leaf_size}};
    // Only when set: older readers know no such keys.
    if (r.transparent_shadows) out["transparent_shadows"] = true;
    if (r.spawn_rules != SpawnRules::Tracer) out["spawn_rules"] = spawn_rules_name(r.spawn_rules);
    if (r.encoding != Encoding::Linear) out["encoding"] = encoding_name(r.encoding);
    if (r.antialias == Antialias::Adaptive) {
        out["antialias"] = antialias_name(r.antialias);
        out["adaptive_threshold"] = r.adaptive_threshold;
        out["adaptive_depth"] = r.adaptive_depth;
        out["adaptive_cell"] = r.adaptive_cell;
    }
    return out;
}

// A light's entry: its kind's fields only (an area light's edges and samples, a spotlight's cone).
static Json light_json(const Light& l) {
    Json entry = {{"color", vec(l.color)}};
    if (l.kind != Light::Kind::Parallel) entry["position"] = vec(l.position);
    if (l.edge1 != dvec3(0.0) || l.edge2 != dvec3(0.0)) {  // an area light
        entry["edge1"] = vec(l.edge1);
        entry["edge2"] = vec(l.edge2);
        entry["samples"] = {l.samples1, l.samples2};
        if (l.shape != Light::Shape::Rectangle) entry["shape"] = l.shape == Light::Shape::Disc ? "disc" : "sphere";
        if (l.jitter) entry["jitter"] = true;
        if (l.adaptive) entry["adaptive"] = true;
    }
    if (l.kind == Light::Kind::Spot) {
        entry["kind"] = "spot";
        entry["direction"] = vec(l.direction);
        entry["radius"] = l.radius;
        entry["falloff"] = l.falloff;
        entry["tightness"] = l.tightness;
    } else if (l.kind == Light::Kind::Parallel) {
        entry["kind"] = "parallel";
        entry["direction"] = vec(l.direction);
    }
    if (l.fade_distance > 0) {
        entry["fade_distance"] = l.fade_distance;
        entry["fade_power"] = l.fade_power;
    }
    return entry;
}

// Every shape and light of the scene as arrays of `out` (later: see add_array).
void add_shapes(Json& out, const SceneDescription& scene, const SceneMeshes* meshes, std::vector<LaterArray>* later) {
    add_array(
        out, "spheres", scene.spheres, [&scene](const Sphere& s) { return sphere_json(scene, s); }, later);
    add_array(
        out, "planes", scene.planes, [&scene](const Plane& p) { return plane_json(scene, p); }, later);
    add_array(
        out, "meshes", scene.meshes.size(),
        [&scene, meshes](size_t block) {  // called after scene_json returns: `meshes` by value
            const Mesh& m = scene.meshes[block];
            Json entry = placed_json(scene, m, {{"file", m.path}});
            if (m.flat) entry["shading"] = "flat";  // only then: the default is implied
            if (meshes && block < meshes->file_of_block.size()) {
                const MeshFacts facts = mesh_facts(*meshes->files[meshes->file_of_block[block]], m);
                entry["triangles"] = facts.triangles;
                entry["vertices"] = facts.vertices;
                entry["bounds"] = {vec(facts.lower), vec(facts.upper)};
            }
            return entry;
        },
        later);
    add_array(
        out, "triangles", scene.triangles,
        [&scene](const FlatTriangle& t) -> Json {
            return placed_json(scene, t, {{"a", vec(t.a)}, {"b", vec(t.b)}, {"c", vec(t.c)}});
        },
        later);
    add_array(
        out, "quads", scene.quads,
        [&scene](const Quad& q) -> Json {
            return placed_json(scene, q, {{"corner", vec(q.corner)}, {"edge1", vec(q.edge1)}, {"edge2", vec(q.edge2)}});
        },
        later);
    add_array(
        out, "boxes", scene.boxes, [&scene](const Box& b) { return box_json(scene, b); }, later);
    if (!scene.cones.empty())  // only then: older readers know no such key
        add_array(
            out, "cones", scene.cones, [&scene](const Cone& cone) { return cone_json(scene, cone); }, later);
    if (!scene.discs.empty())
        add_array(
            out, "discs", scene.discs,
            [&scene](const Disc& d) -> Json {
                return {{"center", vec(d.center)},
                        {"normal", vec(d.normal)},
                        {"radius", d.radius},
                        {"material", material_json(scene, d.material)}};
            },
            later);
    if (!scene.solids.empty())
        add_array(
            out, "solids", scene.solids, [&scene](const Solid& solid) { return solid_json(scene, solid); }, later);
    add_array(
        out, "lights", scene.lights, [](const Light& l) { return light_json(l); }, later);
}

Json scene_json(const SceneDescription& scene, const SceneMeshes* meshes, std::vector<LaterArray>* later) {
    Json out;
    out["format"] = "tracer-scene";
    out["version"] = 1;
    out["source"] = scene.source_path;
    if (!scene.parameters.empty()) {  // only then: older readers know no such key
        out["parameters"] = Json::object();
        for (const Parameter& p : scene.parameters)
            out["parameters"][p.name] = p.vector ? Json(p.value) : Json(p.value.at(0));
    }
    out["render"] = render_json(scene.render);
    const Camera& c = scene.camera;
    out["camera"] = {{"eye", vec(c.eye)},
                     {"lookat", vec(c.lookat)},
                     {"up", vec(c.up)},
                     {"fovy", c.fovy_degrees},
                     {"focal", c.focal}};
    add_shapes(out, scene, meshes, later);
    return out;
}

}  // namespace

Json scene_to_json(const SceneDescription& scene, const SceneMeshes* meshes) {
    return scene_json(scene, meshes, nullptr);
}

void write_scene_json(std::ostream& stream, const SceneDescription& scene, const SceneMeshes* meshes) {
    std::vector<LaterArray> later;
    const std::string document = text_of(scene_json(scene, meshes, &later));
    // Each array where its placeholder is (keys are sorted in the text), entry by entry,
    // indented as dump(2) indents it.
    std::vector<std::pair<size_t, const LaterArray*>> places;
    for (const LaterArray& array : later)
        places.emplace_back(document.find("\"\\u0001array:" + array.key + "\""), &array);
    std::sort(places.begin(), places.end());
    size_t written = 0;
    for (const auto& [at, array] : places) {
        stream.write(document.data() + written, std::streamsize(at - written));
        written = at + array->key.size() + 14;  // the quoted placeholder: "\u0001array:KEY"
        if (array->count == 0) {
            stream << "[]";
            continue;
        }
        stream << "[\n";
        for (size_t i = 0; i < array->count; ++i) {
            std::string entry = "    " + text_of(array->entry(i));
            for (size_t line = entry.find('\n'); line != std::string::npos; line = entry.find('\n', line + 5))
                entry.replace(line, 1, "\n    ");
            stream << entry << (i + 1 < array->count ? ",\n" : "\n");
        }
        stream << "  ]";
    }
    stream.write(document.data() + written, std::streamsize(document.size() - written));
    stream << '\n';
}

}  // namespace tracer
