#include "scene/scene_json.h"

#include "scene/mesh_facts.h"

namespace tracer {
namespace {

using Json = nlohmann::ordered_json;

Json vec(const dvec3& v) {
    return Json::array({v.x, v.y, v.z});
}

Json material_json(const SceneDescription& scene, int index) {
    const Material& m = scene.materials.at(size_t(index));
    return Json{{"name", m.name},  {"ka", vec(m.ka)}, {"kd", vec(m.kd)}, {"ks", vec(m.ks)},
                {"km", vec(m.km)}, {"n", m.n},        {"kt", vec(m.kt)}, {"ior", m.ior}};
}

// Where a shape is placed: its scale, rotate and translate keys, or its transform's steps.
void add_placement(Json& out, const Placed& placed) {
    if (placed.steps.empty()) {
        out["scale"] = vec(placed.scale);
        out["rotate"] = {{"axis", vec(placed.rotate_axis)}, {"angle", placed.rotate_degrees}};
        out["translate"] = vec(placed.translate);
        return;
    }
    out["transform"] = Json::array();
    for (const TransformStep& step : placed.steps) {
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

}  // namespace

Json scene_to_json(const SceneDescription& scene, const SceneMeshes* meshes) {
    Json out;
    out["format"] = "tracer-scene";
    out["version"] = 1;
    out["source"] = scene.source_path;
    if (!scene.parameters.empty()) {  // only then: older readers know no such key
        out["parameters"] = Json::object();
        for (const Parameter& p : scene.parameters)
            out["parameters"][p.name] = p.vector ? Json(p.value) : Json(p.value.at(0));
    }
    const RenderSettings& r = scene.render;
    out["render"] = {{"width", r.width},
                     {"height", r.height},
                     {"max_depth", r.max_depth},
                     {"samples", r.samples},
                     {"background", vec(r.background)},
                     {"shadows", r.shadows},
                     {"accel", accelerator_name(r.accel)},
                     {"leaf_size", r.leaf_size}};
    // Only when set: older readers know no such keys.
    if (r.transparent_shadows) out["render"]["transparent_shadows"] = true;
    if (r.spawn_rules == SpawnRules::Spd) out["render"]["spawn_rules"] = "spd";
    if (r.antialias == Antialias::Adaptive) {
        out["render"]["antialias"] = "adaptive";
        out["render"]["adaptive_threshold"] = r.adaptive_threshold;
        out["render"]["adaptive_depth"] = r.adaptive_depth;
    }
    const Camera& c = scene.camera;
    out["camera"] = {{"eye", vec(c.eye)},
                     {"lookat", vec(c.lookat)},
                     {"up", vec(c.up)},
                     {"fovy", c.fovy_degrees},
                     {"focal", c.focal}};
    out["spheres"] = Json::array();
    for (const Sphere& s : scene.spheres)
        out["spheres"].push_back(
            {{"center", vec(s.center)}, {"radius", s.radius}, {"material", material_json(scene, s.material)}});
    out["planes"] = Json::array();
    for (const Plane& p : scene.planes)
        out["planes"].push_back(
            {{"point", vec(p.point)}, {"normal", vec(p.normal)}, {"material", material_json(scene, p.material)}});
    out["meshes"] = Json::array();
    for (size_t block = 0; block < scene.meshes.size(); ++block) {
        const Mesh& m = scene.meshes[block];
        Json entry = placed_json(scene, m, {{"file", m.path}});
        if (m.flat) entry["shading"] = "flat";  // only then: the default is implied
        if (meshes && block < meshes->file_of_block.size()) {
            const MeshFacts facts = mesh_facts(meshes->files[meshes->file_of_block[block]], m);
            entry["triangles"] = facts.triangles;
            entry["vertices"] = facts.vertices;
            entry["bounds"] = {vec(facts.lower), vec(facts.upper)};
        }
        out["meshes"].push_back(entry);
    }
    out["triangles"] = Json::array();
    for (const FlatTriangle& t : scene.triangles)
        out["triangles"].push_back(placed_json(scene, t, {{"a", vec(t.a)}, {"b", vec(t.b)}, {"c", vec(t.c)}}));
    out["quads"] = Json::array();
    for (const Quad& q : scene.quads)
        out["quads"].push_back(
            placed_json(scene, q, {{"corner", vec(q.corner)}, {"edge1", vec(q.edge1)}, {"edge2", vec(q.edge2)}}));
    out["boxes"] = Json::array();
    for (const Box& b : scene.boxes)
        out["boxes"].push_back(placed_json(scene, b, {{"min", vec(b.min)}, {"max", vec(b.max)}}));
    if (!scene.cones.empty()) {  // only then: older readers know no such key
        out["cones"] = Json::array();
        for (const Cone& cone : scene.cones)
            out["cones"].push_back({{"base", vec(cone.base)},
                                    {"top", vec(cone.top)},
                                    {"base_radius", cone.base_radius},
                                    {"top_radius", cone.top_radius},
                                    {"caps", cone.caps},
                                    {"material", material_json(scene, cone.material)}});
    }
    if (!scene.discs.empty()) {
        out["discs"] = Json::array();
        for (const Disc& d : scene.discs)
            out["discs"].push_back({{"center", vec(d.center)},
                                    {"normal", vec(d.normal)},
                                    {"radius", d.radius},
                                    {"material", material_json(scene, d.material)}});
    }
    out["lights"] = Json::array();
    for (const Light& l : scene.lights)
        out["lights"].push_back({{"position", vec(l.position)}, {"color", vec(l.color)}});
    return out;
}

}  // namespace tracer
