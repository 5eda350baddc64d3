#include "app/summary.h"

#include <algorithm>
#include <cstdio>
#include <utility>
#include <vector>

#include "render/whitted.h"

namespace tracer {
namespace {

std::string millions(uint64_t count) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f M", double(count) / 1e6);
    return text;
}

// Samples per pixel as the summary line gives them: N*N, or adaptive's mean.
std::string samples_text(const RenderSettings& render, const RayCounts& rays, const Image& image) {
    if (render.antialias == Antialias::Uniform) return std::to_string(render.samples);
    char text[64];
    const double pixels = std::max(1.0, double(image.width) * double(image.height));
    std::snprintf(text, sizeof text, "%.2f (adaptive)", double(rays.primary) / pixels);
    return text;
}

}  // namespace

std::string render_summary(const std::string& output, const Image& image, const RenderSettings& render,
                           const RenderStats& stats) {
    const RayCounts& rays = stats.rays;
    const std::string refraction = rays.refraction ? ", " + millions(rays.refraction) + " refraction" : "";
    char text[512];
    std::snprintf(text, sizeof text,
                  "%dx%d, %s spp, %d threads, %.3f s, %srays (%s primary, %s shadow, %s reflection%s), %.1f Mrays/s",
                  image.width, image.height, samples_text(render, rays, image).c_str(), stats.threads, stats.seconds,
                  millions(rays.total()).c_str(), millions(rays.primary).c_str(), millions(rays.shadow).c_str(),
                  millions(rays.reflection).c_str(), refraction.c_str(), double(rays.total()) / stats.seconds / 1e6);
    return output + ": " + text;
}

std::string trees_cut_note(const RenderStats& stats) {
    if (stats.rays.trees_cut == 0) return "";
    char text[256];
    std::snprintf(text, sizeof text,
                  "tracer: note: %llu camera rays reached the bound of %d reflected and refracted rays; the rest of "
                  "their ray trees returned black (README, Limits)",
                  (unsigned long long)stats.rays.trees_cut, kMostRaysPerTree);
    return text;
}

std::string scene_counts(const SceneDescription& scene) {
    size_t cylinders = 0;
    for (const Cone& cone : scene.cones) cylinders += cone.base_radius == cone.top_radius;
    const size_t roots = size_t(
        std::count_if(scene.solids.begin(), scene.solids.end(), [](const Solid& solid) { return !solid.nested; }));
    // (count, singular, plural, said even when 0)
    struct Count {
        size_t count;
        const char* one;
        const char* many;
        bool always;
    };
    const std::vector<Count> counts = {
        {scene.spheres.size(), "sphere", "spheres", true}, {scene.planes.size(), "plane", "planes", true},
        {scene.meshes.size(), "mesh", "meshes", true},     {scene.triangles.size(), "triangle", "triangles", false},
        {scene.quads.size(), "quad", "quads", false},      {scene.boxes.size(), "box", "boxes", false},
        {cylinders, "cylinder", "cylinders", false},       {scene.cones.size() - cylinders, "cone", "cones", false},
        {scene.discs.size(), "disc", "discs", false},      {roots, "solid", "solids", false},
        {scene.lights.size(), "light", "lights", true},    {scene.materials.size(), "material", "materials", true},
    };
    std::string out;
    for (const Count& c : counts) {
        if (c.count == 0 && !c.always) continue;
        out += (out.empty() ? "" : ", ") + std::to_string(c.count) + " " + (c.count == 1 ? c.one : c.many);
    }
    return out;
}

}  // namespace tracer
