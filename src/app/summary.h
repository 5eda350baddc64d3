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

// The note printed when camera rays reached the bound of their ray trees, or "" when none did.
std::string trees_cut_note(const RenderStats& stats);

}  // namespace tracer
