#include "scene/scene.h"

#include <cmath>
#include <cstdio>

namespace tracer {

const char* accelerator_name(Accelerator accelerator) {
    switch (accelerator) {
        case Accelerator::None: return "none";
        case Accelerator::Box: return "box";
        case Accelerator::Median: return "median";
        case Accelerator::Sah: return "sah";
    }
    return "sah";
}

std::string render_settings_problem(const RenderSettings& render) {
    if (render.antialias == Antialias::Adaptive && render.samples > 1)
        return "'samples' is for uniform antialiasing; adaptive places its own samples (at most "
               "(2^adaptive_depth + 1)^2 per pixel): leave 'samples' at 1";
    if (render.antialias == Antialias::Adaptive && std::ldexp(render.adaptive_cell, render.adaptive_depth) < 1) {
        char cell[32];
        std::snprintf(cell, sizeof cell, "%g", render.adaptive_cell);
        return std::string("'adaptive_cell' ") + cell + " is finer than the 1/" +
               std::to_string(1 << render.adaptive_depth) + " pixel that 'adaptive_depth' " +
               std::to_string(render.adaptive_depth) + " splits down to: raise the depth or the cell";
    }
    const long long pixels = 1LL * render.width * render.height;
    if (pixels <= kMaxPixels) return "";
    return "the image would have " + std::to_string(pixels) + " pixels; the limit is " + std::to_string(kMaxPixels) +
           " (8192 x 8192)";
}

bool accelerator_from_name(std::string_view name, Accelerator& out) {
    for (Accelerator a : {Accelerator::None, Accelerator::Box, Accelerator::Median, Accelerator::Sah})
        if (name == accelerator_name(a)) {
            out = a;
            return true;
        }
    return false;
}

}  // namespace tracer
