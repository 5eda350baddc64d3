// The line a render ends with: what was written, its size and samples, time and rays.
#pragma once

#include <string>

#include "base/image.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace tracer {

// "out.png: 1200x800, 1 spp, 2 threads, 0.210 s, 3.1 M rays (...), 14.8 Mrays/s" (no newline).
std::string render_summary(const std::string& output, const Image& image, const RenderSettings& render,
                           const RenderStats& stats);

// "4 spheres, 1 plane, 0 meshes, 1 cylinder, 2 cones, 2 lights, 5 materials": --check's counts,
// the kinds every scene is asked about always, the others where there are some.
std::string scene_counts(const SceneDescription& scene);

// The note printed when camera rays reached the bound of their ray trees, or "" when none did.
std::string trees_cut_note(const RenderStats& stats);

}  // namespace tracer
