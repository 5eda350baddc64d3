#include "render/render_stats.h"

#include <cstdio>

namespace tracer {

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
    out["rays"] = {{"primary", rays.primary}, {"shadow", rays.shadow}, {"reflection", rays.reflection},
                   {"total", rays.total()}};
    const double total = double(std::max<uint64_t>(rays.total(), 1));
    out["box_tests_per_ray"] = double(rays.traversal.box_tests) / total;
    out["triangle_tests_per_ray"] = double(rays.traversal.primitive_tests) / total;
    out["mrays_per_second"] = double(rays.total()) / stats.seconds / 1e6;
    out["meshes"] = nlohmann::ordered_json::array();
    for (const MeshAccel& mesh : world.meshes()) {
        const BvhStats bvh = mesh.bvh().stats();
        out["meshes"].push_back({{"triangles", mesh.mesh().vertices.size()},
                                 {"build_seconds", mesh.build_seconds()},
                                 {"nodes", bvh.nodes},
                                 {"leaves", bvh.leaves},
                                 {"depth", bvh.depth},
                                 {"leaf_size_min", bvh.min_leaf},
                                 {"leaf_size_mean", bvh.mean_leaf},
                                 {"leaf_size_max", bvh.max_leaf}});
    }
    return out;
}

std::string render_stats_text(const nlohmann::ordered_json& s) {
    char line[256];
    std::string out;
    for (const auto& mesh : s["meshes"]) {
        std::snprintf(line, sizeof line,
                      "mesh: %zu triangles, %s built in %.3f ms: %zu nodes, %zu leaves, depth %d, leaf size "
                      "%zu..%zu (mean %.2f)\n",
                      mesh["triangles"].get<size_t>(), s["accel"].get<std::string>().c_str(),
                      mesh["build_seconds"].get<double>() * 1e3, mesh["nodes"].get<size_t>(),
                      mesh["leaves"].get<size_t>(), mesh["depth"].get<int>(), mesh["leaf_size_min"].get<size_t>(),
                      mesh["leaf_size_max"].get<size_t>(), mesh["leaf_size_mean"].get<double>());
        out += line;
    }
    const auto& rays = s["rays"];
    std::snprintf(line, sizeof line,
                  "rays: %llu primary, %llu shadow, %llu reflection; per ray %.2f box tests, %.2f triangle tests; "
                  "%.3f s, %.1f Mrays/s\n",
                  (unsigned long long)rays["primary"].get<uint64_t>(), (unsigned long long)rays["shadow"].get<uint64_t>(),
                  (unsigned long long)rays["reflection"].get<uint64_t>(), s["box_tests_per_ray"].get<double>(),
                  s["triangle_tests_per_ray"].get<double>(), s["render_seconds"].get<double>(),
                  s["mrays_per_second"].get<double>());
    return out + line;
}

}  // namespace tracer
