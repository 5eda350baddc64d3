#include "app/summary.h"

#include <algorithm>
#include <cstdio>

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

}  // namespace tracer
