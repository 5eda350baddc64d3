#include "scene/scene_json.h"

namespace tracer {
namespace {

using Json = nlohmann::ordered_json;

Json vec(const dvec3& v) { return Json::array({v.x, v.y, v.z}); }

Json material_json(const SceneDescription& scene, int index) {
    const Material& m = scene.materials.at(size_t(index));
    return Json{{"name", m.name}, {"ka", vec(m.ka)}, {"kd", vec(m.kd)}, {"ks", vec(m.ks)},
                {"km", vec(m.km)}, {"n", m.n}, {"kt", vec(m.kt)}, {"ior", m.ior}};
}

}  // namespace

Json scene_to_json(const SceneDescription& scene) {
    Json out;
    out["format"] = "tracer-scene";
    out["version"] = 1;
    out["source"] = scene.source_path;
    const RenderSettings& r = scene.render;
    out["render"] = {{"width", r.width},          {"height", r.height},
                     {"max_depth", r.max_depth},  {"samples", r.samples},
                     {"background", vec(r.background)}, {"shadows", r.shadows},
                     {"accel", accelerator_name(r.accel)}, {"leaf_size", r.leaf_size}};
    const Camera& c = scene.camera;
    out["camera"] = {{"eye", vec(c.eye)}, {"lookat", vec(c.lookat)}, {"up", vec(c.up)},
                     {"fovy", c.fovy_degrees}, {"focal", c.focal}};
    out["spheres"] = Json::array();
    for (const Sphere& s : scene.spheres)
        out["spheres"].push_back(
            {{"center", vec(s.center)}, {"radius", s.radius}, {"material", material_json(scene, s.material)}});
    out["planes"] = Json::array();
    for (const Plane& p : scene.planes)
        out["planes"].push_back(
            {{"point", vec(p.point)}, {"normal", vec(p.normal)}, {"material", material_json(scene, p.material)}});
    out["meshes"] = Json::array();
    for (const Mesh& m : scene.meshes) {
        out["meshes"].push_back({{"file", m.path},
                                 {"scale", vec(m.scale)},
                                 {"rotate", {{"axis", vec(m.rotate_axis)}, {"angle", m.rotate_degrees}}},
                                 {"translate", vec(m.translate)},
                                 {"material", material_json(scene, m.material)}});
        if (m.flat) out["meshes"].back()["shading"] = "flat";  // only then: the default is implied
    }
    out["lights"] = Json::array();
    for (const Light& l : scene.lights)
        out["lights"].push_back({{"position", vec(l.position)}, {"color", vec(l.color)}});
    return out;
}

}  // namespace tracer
