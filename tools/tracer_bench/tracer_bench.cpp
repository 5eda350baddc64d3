// tracer_bench: times tracer's BVH build and render loop in-process, the way
// ../shared/bench/embree-whitted times Embree, so the two compare side by side (abab.py).
// Process start, parsing, OBJ loading and image writing are not timed. Prints a report on
// stderr and, with --json, one JSON object on stdout.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "auto_crop.h"
#include "base/parallel.h"
#include "bench_scene.h"
#include "io/image_file.h"
#include "io/obj_mesh.h"
#include "render/camera.h"
#include "render/render_stats.h"
#include "render/renderer.h"

namespace {

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

}  // namespace

int main(int argc, char** argv) {
    std::string scene_path = "scenes/bunny.scn", accel, obj, png, crop_text;
    int leaf_size = 0, threads = 0, runs = 11;
    bool json = false;
    CLI::App app{"tracer_bench: in-process build and render timings of a scene"};
    app.add_option("scene", scene_path, "The scene (default scenes/bunny.scn)");
    app.add_option("--accel", accel, "none, box, median or sah (default: the scene's)");
    app.add_option("--leaf-size", leaf_size, "BVH leaf size (default: the scene's)");
    app.add_option("--threads", threads, "Render threads (default: every core)");
    app.add_option("--runs", runs, "Timed renders (median reported) and builds")->check(CLI::Range(1, 1000));
    app.add_option("--obj", obj, "Use this OBJ file for the scene's first mesh");
    app.add_option("--crop", crop_text, "auto (the meshes' projected bounds + 4 px) or 'X0 Y0 W H'");
    app.add_option("--png", png, "Also write the image of the last render");
    app.add_flag("--json", json, "Print one JSON object on stdout");
    bool flatten = false;
    app.add_flag("--flatten", flatten, "Merge every mesh block into one placed mesh, shared files too (no instancing)");
    CLI11_PARSE(app, argc, argv);

    // Step 1: the scene and its meshes (not timed).
    tracer::Accelerator chosen{};
    if (!accel.empty() && !tracer::accelerator_from_name(accel, chosen)) {
        std::cerr << "tracer_bench: unknown accelerator '" << accel << "'\n";
        return 2;
    }
    std::optional<tracer::LoadedScene> loaded = tracer::load_bench_scene(scene_path, obj, leaf_size);
    if (!loaded) return 1;
    if (!accel.empty()) loaded->scene.render.accel = chosen;
    const tracer::SceneDescription& scene = loaded->scene;
    const tracer::SceneMeshes& meshes = loaded->meshes;

    tracer::RenderOptions options;
    options.threads = threads;
    if (crop_text == "auto") {
        options.crop = tracer::auto_crop(scene, meshes);
    } else if (!crop_text.empty()) {
        std::istringstream in(crop_text);
        in >> options.crop.x0 >> options.crop.y0 >> options.crop.width >> options.crop.height;
    }

    // Step 2: builds. The first is a warm-up; the world of the last one is rendered.
    std::vector<double> build_ms;
    std::optional<tracer::World> world;
    for (int i = 0; i <= runs; ++i) {
        world.emplace(scene, meshes, threads, flatten);  // build threads follow --threads, as in embree_bench
        double ms = world->top_level_build_seconds() * 1e3;
        for (const auto& mesh : world->meshes()) ms += mesh.build_seconds() * 1e3;
        if (i > 0) build_ms.push_back(ms);
    }

    // Step 3: renders, one untimed warm-up first, on threads started once (as embree_bench's).
    options.threads = threads;
    tracer::Image image;
    tracer::RenderStats stats;
    tracer::render(*world, scene, options, image, stats);
    std::vector<double> render_ms;
    for (int i = 0; i < runs; ++i) {
        tracer::render(*world, scene, options, image, stats);
        render_ms.push_back(stats.seconds * 1e3);
    }
    if (!png.empty()) tracer::write_image(png, image);

    // Step 4: report.
    size_t triangles = 0;
    for (uint32_t file : meshes.file_of_block) triangles += meshes.files[file]->triangles.size();
    const tracer::RayCounts& rays = stats.rays;
    const auto figures = tracer::render_stats_json(*world, scene, stats);  // of the last render
    nlohmann::ordered_json out;
    out["scene"] = scene_path;
    out["accel"] = figures["accel"];
    out["leaf_size"] = figures["leaf_size"];
    out["triangles"] = triangles;
    out["threads"] = stats.threads;
    out["runs"] = runs;
    out["crop"] =
        options.crop.width > 0
            ? nlohmann::ordered_json::array({options.crop.x0, options.crop.y0, options.crop.width, options.crop.height})
            : nlohmann::ordered_json("full_frame");
    out["build_ms"] = median(build_ms);
    out["render_ms_median"] = median(render_ms);
    out["render_ms_min"] = *std::min_element(render_ms.begin(), render_ms.end());
    out["render_ms"] = render_ms;
    out["rays"] = rays.total();
    out["primary"] = rays.primary;
    out["shadow"] = rays.shadow;
    out["mrays_per_s"] = double(rays.total()) / median(render_ms) / 1e3;
    out["box_tests_per_ray"] = figures["box_tests_per_ray"];
    out["triangle_tests_per_ray"] = figures["triangle_tests_per_ray"];
    out["object_tests_per_ray"] = figures["object_tests_per_ray"];
    out["objects"] = figures["objects"];
    out["flatten"] = flatten;
    size_t memory = world->top_level_memory_bytes();
    for (const auto& mesh : world->meshes()) memory += mesh.memory_bytes();
    out["memory_bytes"] = memory;
    std::cerr << "tracer_bench: " << out["accel"].get<std::string>() << ", " << triangles << " triangles, "
              << stats.threads << " threads, crop " << out["crop"].dump() << ": build " << out["build_ms"].get<double>()
              << " ms, render " << out["render_ms_median"].get<double>() << " ms (median of " << runs << "), "
              << out["mrays_per_s"].get<double>() << " Mrays/s\n";
    if (json) std::cout << out.dump() << '\n';
    return 0;
}
