#include "scene/scene.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <utility>

#include "scene/words.h"

namespace tracer {
namespace {

constexpr Words<Accelerator, 4> kAcceleratorWords{{{Accelerator::None, "none"},
                                                   {Accelerator::Box, "box"},
                                                   {Accelerator::Median, "median"},
                                                   {Accelerator::Sah, "sah"}}};
constexpr Words<SpawnRules, 2> kSpawnRulesWords{{{SpawnRules::Tracer, "tracer"}, {SpawnRules::Spd, "spd"}}};
constexpr Words<Antialias, 2> kAntialiasWords{{{Antialias::Uniform, "uniform"}, {Antialias::Adaptive, "adaptive"}}};
constexpr Words<Encoding, 2> kEncodingWords{{{Encoding::Linear, "linear"}, {Encoding::Srgb, "srgb"}}};

}  // namespace

const char* accelerator_name(Accelerator accelerator) {
    return word_of(kAcceleratorWords, accelerator);
}
bool accelerator_from_name(std::string_view name, Accelerator& out) {
    return value_of(kAcceleratorWords, name, out);
}
const char* spawn_rules_name(SpawnRules rules) {
    return word_of(kSpawnRulesWords, rules);
}
bool spawn_rules_from_name(std::string_view name, SpawnRules& out) {
    return value_of(kSpawnRulesWords, name, out);
}
const char* antialias_name(Antialias antialias) {
    return word_of(kAntialiasWords, antialias);
}
bool antialias_from_name(std::string_view name, Antialias& out) {
    return value_of(kAntialiasWords, name, out);
}
const char* encoding_name(Encoding encoding) {
    return word_of(kEncodingWords, encoding);
}
bool encoding_from_name(std::string_view name, Encoding& out) {
    return value_of(kEncodingWords, name, out);
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

}  // namespace tracer
