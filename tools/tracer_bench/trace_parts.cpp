// trace_parts: where a frame's time goes, part by part, on one thread: the rays of the
// hit-dominated crop (or the full frame) are made once, then each query is timed on its own
// (fastest of 15 passes): the box test's set-up (TraversalRay), the nearest-hit query of the
// mesh and of the whole world, ray by ray and in packets of 2 x 4 (accel/ray_packet.h), the
// shadow rays' any-hit query, the mesh's nearest hit for mirror rays from the primary hits
// (secondary rays), trace() and render(); for the mesh queries also the box and triangle tests
// per ray. Used to compare two builds of the renderer run by run (tools/bench compare-builds).
//
//   build/release/trace_parts [scene] [--full] [--repeat K] [--leaf-size N] [--obj FILE]
//
// --repeat K traces every primary ray K times in a row: the branch predictor then learns each
// ray's path, so the time saved is roughly what mispredicted branches cost.

#include <algorithm>
#include <chrono>
#include <iostream>
#include <type_traits>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/geometric.hpp>

#include "accel/ray_packet.h"
#include "accel/world.h"
#include "auto_crop.h"
#include "bench_scene.h"
#include "io/obj_mesh.h"
#include "render/camera.h"
#include "render/renderer.h"
#include "render/spawn.h"
#include "render/whitted.h"

namespace {

using namespace tracer;

// The fastest of 15 runs of f, in milliseconds: the time f returns, or (f returns nothing)
// the time f takes.
template <typename F>
double fastest_ms(F f) {
    double best = 1e300;
    for (int run = 0; run < 15; ++run) {
        const auto start = std::chrono::steady_clock::now();
        if constexpr (std::is_same_v<decltype(f()), double>) {
            best = std::min(best, f());
        } else {
            f();
            best = std::min(
                best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        }
    }
    return best;
}

volatile double sink;  // keeps the timed loops' results alive

void report(const char* part, double ms, size_t rays) {
    std::cout << part << ' ' << ms << " ms (" << ms * 1e6 / double(rays) << " ns per ray, " << rays << " rays)\n";
}

// The work of one pass of a query, per ray, on a line the caller ends.
void report_work(const tracer::TraversalCounts& counts, size_t rays) {
    std::cout << "  per ray: " << double(counts.box_tests) / double(rays) << " box tests, "
              << double(counts.primitive_tests) / double(rays) << " triangle tests";
}

}  // namespace

int main(int argc, char** argv) {
    std::string scene_path = "scenes/bunny.scn";
    bool full = false;
    int repeat = 1;
    CLI::App app{"trace_parts: one thread's time per query, crop or full frame"};
    app.add_option("scene", scene_path, "The scene (default scenes/bunny.scn)");
    app.add_flag("--full", full, "The whole frame instead of the meshes' crop");
    app.add_option("--repeat", repeat, "Trace each primary ray this many times in a row")->check(CLI::Range(1, 64));
    int leaf_size = 0;
    app.add_option("--leaf-size", leaf_size, "Override the scene's BVH leaf size")->check(CLI::Range(1, 255));
    std::string obj;
    app.add_option("--obj", obj, "Use this OBJ file for the scene's first mesh");
    CLI11_PARSE(app, argc, argv);

    // Step 1: the scene, its world on one thread, and the rays.
    const std::optional<LoadedScene> loaded = load_bench_scene(scene_path, obj, leaf_size);
    if (!loaded || loaded->meshes.files.empty()) return 1;
    const SceneDescription& scene = loaded->scene;
    const SceneMeshes& meshes = loaded->meshes;
    const PixelRect crop = full ? PixelRect{0, 0, scene.render.width, scene.render.height} : auto_crop(scene, meshes);
    const World world(scene, meshes, 1);
    const MeshAccel& mesh = world.meshes()[0];
    const PinholeCamera camera(scene.camera, scene.render.width, scene.render.height);
    std::vector<Ray> primary;
    for (int y = crop.y0; y < crop.y0 + crop.height; ++y)
        for (int x = crop.x0; x < crop.x0 + crop.width; ++x)
            for (int k = 0; k < repeat; ++k) primary.push_back(camera.ray_through(x + 0.5, y + 0.5));
    std::vector<std::pair<Ray, Interval>> shadow;     // from every hit to every light
    std::vector<std::pair<Ray, Interval>> reflected;  // from every hit, its mirror direction
    SearchCounts counts;
    // The nearest hit's surface, as the Whitted loop finds it.
    auto nearest_surface = [&](const Ray& ray) -> std::optional<SurfaceHit> {
        const auto hit = world.nearest_hit(ray, kPrimaryRange, counts);
        if (!hit) return std::nullopt;
        return world.surface(ray, *hit);
    };
    for (const Ray& ray : primary) {
        const auto hit = nearest_surface(ray);
        if (!hit) continue;
        const SpawnedRay mirror = spawn_ray(*hit, glm::reflect(ray.direction, hit->geometric_normal));
        reflected.push_back({mirror.ray, mirror.range});
        for (const Light& light : world.lights()) {
            const SpawnedRay ray_to_light = spawn_ray_to(*hit, Vec3(light.position));
            shadow.push_back({ray_to_light.ray, ray_to_light.range});
        }
    }

    // Step 2: each part on its own.
    report("TraversalRay   ", fastest_ms([&] {
               float sum = 0;
               for (const Ray& ray : primary) {
                   // Every field read: with one, the compiler builds only that one.
                   const TraversalRay r(ray, kPrimaryRange);
                   for (int axis = 0; axis < 3; ++axis)
                       sum += r.origin_near[axis] + r.origin_far[axis] + r.inv_dir[axis] + r.inv_dir_far[axis] +
                              r.scaled_origin_near[axis] + r.scaled_origin_far[axis] +
                              float(r.near_row[axis] + r.far_row[axis]);
                   sum += r.t_min + r.t_max + float(r.fused);
               }
               sink = sum;
           }),
           primary.size());
    // The mesh's nearest-hit query of rays 0 .. n (ray_at(i), range_at(i)), timed, its work counted.
    auto time_mesh_nearest = [&](const char* name, size_t n, auto ray_at, auto range_at, TraversalCounts& work) {
        report(name, fastest_ms([&] {
                   double sum = 0;
                   work = {};
                   for (size_t i = 0; i < n; ++i) {
                       const Ray& ray = ray_at(i);
                       Interval range = range_at(i);
                       MeshHit hit;
                       if (world.may_hit(ray) && mesh.intersect(ray, range, hit, work)) sum += range.max;
                   }
                   sink = sum;
               }),
               n);
        report_work(work, n);
        std::cout << '\n';
    };
    TraversalCounts mesh_counts;
    time_mesh_nearest(
        "mesh.intersect ", primary.size(), [&](size_t i) -> const Ray& { return primary[i]; },
        [](size_t) { return kPrimaryRange; }, mesh_counts);
    if (repeat > 1) return 0;
    // The same rays in packets of 2 x 4 (as the renderer's tiles: MeshAccel::intersect_packet),
    // checked against the one-by-one answers; rows past the last pair are left out.
    const size_t row_length = size_t(crop.width);
    auto tiles = [&](auto each_tile) {
        for (size_t row = 0; row + 2 * row_length <= primary.size(); row += 2 * row_length)
            for (size_t i = row; i < row + row_length; i += kPacket / 2) {
                const int columns = int(std::min<size_t>(kPacket / 2, row + row_length - i));
                const Ray* rays[kPacket];
                int n = 0;
                for (int r = 0; r < 2; ++r)
                    for (int c = 0; c < columns; ++c) rays[n++] = &primary[i + size_t(r) * row_length + size_t(c)];
                each_tile(rays, n);
            }
    };
    auto packets = [&](auto each_packet) {
        tiles([&](const Ray* const* rays, int n) {
            Interval ranges[kPacket];
            std::fill(ranges, ranges + n, kPrimaryRange);
            MeshHit hits[kPacket];
            const unsigned found = mesh.intersect_packet(rays, n, ranges, hits, mesh_counts);
            each_packet(rays, n, found, ranges, hits);
        });
    };
    report("mesh.packets   ", fastest_ms([&] {
               double sum = 0;
               mesh_counts = {};
               packets([&](const Ray* const*, int n, unsigned found, const Interval* ranges, const MeshHit*) {
                   for (int k = 0; k < n; ++k)
                       if (found >> k & 1) sum += ranges[k].max;
               });
               sink = sum;
           }),
           primary.size());
    report_work(mesh_counts, primary.size());
    size_t differ = 0;
    packets([&](const Ray* const* rays, int n, unsigned found, const Interval* ranges, const MeshHit* hits) {
        for (int k = 0; k < n; ++k) {
            Interval range = kPrimaryRange;
            MeshHit alone;
            TraversalCounts ignored;
            const bool hit = mesh.intersect(*rays[k], range, alone, ignored);
            const bool same =
                hit == bool(found >> k & 1) && (!hit || (alone.slot == hits[k].slot && range.max == ranges[k].max &&
                                                         alone.hit.u == hits[k].hit.u && alone.hit.v == hits[k].hit.v));
            differ += !same;
        }
    });
    std::cout << "; " << differ << " rays answered differently\n";
    report("world.intersect", fastest_ms([&] {
               double sum = 0;
               for (const Ray& ray : primary)
                   if (const auto hit = nearest_surface(ray)) sum += hit->t;
               sink = sum;
           }),
           primary.size());
    report("world.nearest  ", fastest_ms([&] {
               double sum = 0;
               for (const Ray& ray : primary)
                   if (const auto hit = world.nearest_hit(ray, kPrimaryRange, counts)) sum += hit->t;
               sink = sum;
           }),
           primary.size());
    report("world.packets  ", fastest_ms([&] {
               double sum = 0;
               tiles([&](const Ray* const* rays, int n) {
                   std::optional<Hit> hits[kPacket];
                   world.nearest_hits(rays, n, kPrimaryRange, hits, counts);
                   for (int k = 0; k < n; ++k)
                       if (hits[k]) sum += hits[k]->t;
               });
               sink = sum;
           }),
           primary.size());
    TraversalCounts shadow_counts;
    int blocked = 0;
    report("mesh.occluded  ", fastest_ms([&] {
               blocked = 0;
               shadow_counts = {};
               for (const auto& [ray, range] : shadow)
                   blocked += world.may_hit(ray) && mesh.occluded(ray, range, shadow_counts);
               sink = blocked;
           }),
           shadow.size());
    report_work(shadow_counts, shadow.size());
    std::cout << "; " << blocked << " blocked\n";
    TraversalCounts reflected_counts;
    time_mesh_nearest(
        "mesh.reflected ", reflected.size(), [&](size_t i) -> const Ray& { return reflected[i].first; },
        [&](size_t i) { return reflected[i].second; }, reflected_counts);
    report("trace          ", fastest_ms([&] {
               RayCounts ray_counts;
               double sum = 0;
               for (const Ray& ray : primary) sum += trace(world, scene.render, ray, ray_counts).b;
               sink = sum;
           }),
           primary.size());
    Image image;
    RenderStats stats;
    RenderOptions options;
    options.threads = 1;
    options.crop = crop;
    // The render loop's own time (RenderStats::seconds), as tracer_bench reports it: without
    // clearing the image around the crop.
    report("render         ", fastest_ms([&] {
               render(world, scene, options, image, stats);
               return stats.seconds * 1e3;
           }),
           primary.size());
    return 0;
}
