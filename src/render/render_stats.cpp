#include "render/render_stats.h"

#include <algorithm>
#include <cstdio>

#include "scene/mesh_facts.h"

namespace tracer {
namespace {

nlohmann::ordered_json bvh_json(const Bvh& bvh) {
    const BvhStats s = bvh.stats();
    return {{"nodes", s.nodes},
            {"leaves", s.leaves},
            {"depth", s.depth},
            {"leaf_size_min", s.min_leaf},
            {"leaf_size_mean", s.mean_leaf},
            {"leaf_size_max", s.max_leaf}};
}

// The top level: every object, and the BVH over the bounded ones.
nlohmann::ordered_json objects_json(const World& world) {
    nlohmann::ordered_json top;
    size_t counts[6] = {0, 0, 0, 0, 0, 0};
    for (const Object& object : world.objects()) ++counts[size_t(object.kind)];
    top["spheres"] = counts[size_t(ObjectKind::Sphere)];
    top["planes"] = counts[size_t(ObjectKind::Plane)];
    top["mesh_instances"] = counts[size_t(ObjectKind::MeshInstance)];
    if (const size_t cones = counts[size_t(ObjectKind::Cone)]) top["cones"] = cones;
    if (const size_t discs = counts[size_t(ObjectKind::Disc)]) top["discs"] = discs;
    if (const size_t solids = counts[size_t(ObjectKind::Solid)]) {
        top["solids"] = solids;
        top["solid_leaves"] = world.solids().leaves();
    }
    top["bounded_objects"] = world.bounded_objects();
    top["search"] = world.top_level_linear() ? "linear" : "sah";
    top["build_seconds"] = world.top_level_build_seconds();
    if (!world.top_level_linear()) top["bvh"] = bvh_json(world.top_level());
    top["memory_bytes"] = world.top_level_memory_bytes();
    return top;
}

// The meshes: each mesh file once, however many instances place it; and the shapes each one
// holds (the instances of a shared file, or the blocks and flat shapes merged into a placed mesh).
nlohmann::ordered_json meshes_json(const World& world, const SceneDescription& scene) {
    constexpr size_t kListedShapes = 16;  // "shapes" names the first few; "blocks" counts them all
    // Shape `block` of the mesh blocks, then the triangles, quads and boxes.
    const size_t shapes = scene.meshes.size() + scene.triangles.size() + scene.quads.size() + scene.boxes.size();
    auto label = [&](size_t block) {
        if (block < scene.meshes.size()) return shape_label(scene.meshes[block].path, scene.meshes[block].line);
        block -= scene.meshes.size();
        if (block < scene.triangles.size()) return shape_label("triangle", scene.triangles[block].line);
        block -= scene.triangles.size();
        if (block < scene.quads.size()) return shape_label("quad", scene.quads[block].line);
        return shape_label("box", scene.boxes[block - scene.quads.size()].line);
    };
    std::vector<size_t> blocks_of(world.meshes().size(), 0);
    std::vector<bool> placed(world.meshes().size(), false);
    std::vector<std::string> file_of(world.meshes().size());
    std::vector<nlohmann::ordered_json> shapes_of(world.meshes().size(), nlohmann::ordered_json::array());
    for (size_t block = 0; block < shapes; ++block) {
        // Mesh blocks have an instance each; the flat shapes are all in the merged mesh.
        const MeshInstance* instance =
            block < scene.meshes.size() && block < world.instances().size() ? &world.instances()[block] : nullptr;
        const std::optional<uint32_t> mesh = instance ? std::optional(instance->mesh) : world.merged_mesh();
        if (!mesh) continue;
        placed[*mesh] = instance ? instance->placed : true;
        if (blocks_of[*mesh]++ == 0 && instance) file_of[*mesh] = scene.meshes[block].path;
        if (shapes_of[*mesh].size() < kListedShapes) shapes_of[*mesh].push_back(label(block));
    }
    nlohmann::ordered_json out = nlohmann::ordered_json::array();
    for (size_t i = 0; i < world.meshes().size(); ++i) {
        const MeshAccel& mesh = world.meshes()[i];
        nlohmann::ordered_json entry = {{"file", file_of[i]},  // the first block's
                                        {"triangles", mesh.triangle_count()},
                                        {"placed", bool(placed[i])},  // in world coordinates, merged
                                        {"blocks", blocks_of[i]},
                                        {"shapes", shapes_of[i]},
                                        {"instances", placed[i] ? 0 : blocks_of[i]},
                                        {"build_seconds", mesh.build_seconds()},
                                        {"memory_bytes", mesh.memory_bytes()}};
        if (!mesh.brute_force()) entry.update(bvh_json(mesh.bvh()));
        out.push_back(entry);
    }
    return out;
}

}  // namespace

nlohmann::ordered_json render_stats_json(const World& world, const SceneDescription& scene, const RenderStats& stats) {
    nlohmann::ordered_json out;
    const RayCounts& rays = stats.rays;
    out["width"] = scene.render.width;
    out["height"] = scene.render.height;
    out["samples"] = scene.render.samples;
    out["threads"] = stats.threads;
    out["accel"] = accelerator_name(scene.render.accel);
    out["leaf_size"] = scene.render.leaf_size;
    out["render_seconds"] = stats.seconds;
    out["rays"] = {{"primary", rays.primary},
                   {"primary_hits", rays.primary_hits},
                   {"shadow", rays.shadow},
                   {"reflection", rays.reflection},
                   {"refraction", rays.refraction},
                   {"total", rays.total()},
                   {"total_internal_reflections", rays.total_internal_reflections},
                   {"trees_cut", rays.trees_cut}};
    out["spawn_rules"] = spawn_rules_name(scene.render.spawn_rules);
    out["transparent_shadows"] = scene.render.transparent_shadows;
    const double total = double(std::max<uint64_t>(rays.total(), 1));
    const SearchCounts& work = rays.traversal;
    out["box_tests_per_ray"] = double(work.objects.box_tests + work.triangles.box_tests) / total;
    out["object_box_tests_per_ray"] = double(work.objects.box_tests) / total;
    out["object_tests_per_ray"] = double(work.objects.primitive_tests) / total;
    out["mesh_box_tests_per_ray"] = double(work.triangles.box_tests) / total;
    out["triangle_tests_per_ray"] = double(work.triangles.primitive_tests) / total;
    out["mrays_per_second"] = double(rays.total()) / stats.seconds / 1e6;

    out["objects"] = objects_json(world);
    out["meshes"] = meshes_json(world, scene);
    // The image patterns' files as held: texels, bytes (8-bit files keep one byte a channel).
    if (!world.images().empty()) {
        out["images"] = nlohmann::ordered_json::array();
        for (const ImageFile& image : world.images()) {
            const Texels empty;
            const Texels& texels = image.texels ? *image.texels : empty;
            out["images"].push_back({{"file", image.path},
                                     {"width", texels.width},
                                     {"height", texels.height},
                                     {"channels", texels.channels},
                                     {"eight_bit", !texels.bytes.empty()},
                                     {"memory_bytes", texels.memory_bytes()}});
        }
    }
    return out;
}

std::string render_stats_text(const nlohmann::ordered_json& s) {
    char line[320];
    std::string out;
    const auto& top = s["objects"];
    std::snprintf(line, sizeof line,
                  "objects: %zu spheres, %zu planes, %zu mesh instances; the %zu bounded searched %s",
                  top["spheres"].get<size_t>(), top["planes"].get<size_t>(), top["mesh_instances"].get<size_t>(),
                  top["bounded_objects"].get<size_t>(), top["search"] == "linear" ? "one by one" : "through a BVH");
    out += line;
    if (top.contains("bvh")) {
        const auto& bvh = top["bvh"];
        std::snprintf(line, sizeof line, " built in %.3f ms: %zu nodes, %zu leaves, depth %d",
                      top["build_seconds"].get<double>() * 1e3, bvh["nodes"].get<size_t>(), bvh["leaves"].get<size_t>(),
                      bvh["depth"].get<int>());
        out += line;
    }
    std::snprintf(line, sizeof line, "; %.1f KiB\n", top["memory_bytes"].get<double>() / 1024);
    out += line;
    for (const auto& mesh : s["meshes"]) {
        // The first shape it holds, then the lines of a few more.
        const auto& shapes = mesh["shapes"];
        const size_t blocks = mesh["blocks"].get<size_t>();
        std::string name = shapes.empty() ? mesh["file"].get<std::string>() : shapes[0].get<std::string>();
        if (blocks > 1) {
            name += " and " + std::to_string(blocks - 1) + " more" + (mesh["placed"].get<bool>() ? ", merged" : "");
            constexpr size_t kNamed = 4;
            for (size_t i = 1; i < std::min(shapes.size(), kNamed); ++i)
                name += (i == 1 ? " (" : ", ") + shapes[i].get<std::string>();
            name += blocks > kNamed ? ", ...)" : ")";
        }
        std::snprintf(line, sizeof line, "mesh %s: %zu triangles, %s built in %.3f ms", name.c_str(),
                      mesh["triangles"].get<size_t>(), s["accel"].get<std::string>().c_str(),
                      mesh["build_seconds"].get<double>() * 1e3);
        out += line;
        if (mesh.contains("nodes")) {
            std::snprintf(line, sizeof line, ": %zu nodes, %zu leaves, depth %d, leaf size %zu..%zu (mean %.2f)",
                          mesh["nodes"].get<size_t>(), mesh["leaves"].get<size_t>(), mesh["depth"].get<int>(),
                          mesh["leaf_size_min"].get<size_t>(), mesh["leaf_size_max"].get<size_t>(),
                          mesh["leaf_size_mean"].get<double>());
            out += line;
        }
        const size_t instances = mesh["instances"].get<size_t>();
        const std::string use = instances == 0 ? "placed" : std::to_string(instances) + " instances";
        std::snprintf(line, sizeof line, "; %s; %.1f KiB\n", use.c_str(), mesh["memory_bytes"].get<double>() / 1024);
        out += line;
    }
    if (s.contains("images"))
        for (const auto& image : s["images"]) {
            const double texels = std::max(1.0, double(image["width"].get<int>()) * image["height"].get<int>());
            std::snprintf(line, sizeof line, "image %s: %d x %d texels, %s; %.1f KiB (%.2f bytes a texel)\n",
                          image["file"].get<std::string>().c_str(), image["width"].get<int>(),
                          image["height"].get<int>(), image["eight_bit"].get<bool>() ? "8-bit" : "float",
                          image["memory_bytes"].get<double>() / 1024, image["memory_bytes"].get<double>() / texels);
            out += line;
        }
    const auto& rays = s["rays"];
    std::snprintf(
        line, sizeof line,
        "rays: %llu primary (%llu hit), %llu shadow, %llu reflection, %llu refraction; per ray %.2f object box tests, "
        "%.2f object tests, %.2f mesh box tests, %.2f triangle tests; %.3f s, %.1f Mrays/s\n",
        (unsigned long long)rays["primary"].get<uint64_t>(), (unsigned long long)rays["primary_hits"].get<uint64_t>(),
        (unsigned long long)rays["shadow"].get<uint64_t>(), (unsigned long long)rays["reflection"].get<uint64_t>(),
        (unsigned long long)rays["refraction"].get<uint64_t>(), s["object_box_tests_per_ray"].get<double>(),
        s["object_tests_per_ray"].get<double>(), s["mesh_box_tests_per_ray"].get<double>(),
        s["triangle_tests_per_ray"].get<double>(), s["render_seconds"].get<double>(),
        s["mrays_per_second"].get<double>());
    return out + line;
}

}  // namespace tracer
