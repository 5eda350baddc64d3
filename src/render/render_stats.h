// What the accelerators built and how much work the rays did: `tracer --stats`,
// `--stats-json` and tools/bench report these figures.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "accel/world.h"
#include "render/renderer.h"

namespace tracer {

// Every figure of a finished render, for scripts.
nlohmann::ordered_json render_stats_json(const World& world, const SceneDescription& scene, const RenderStats& stats);

// The same figures as readable lines.
std::string render_stats_text(const nlohmann::ordered_json& stats);

}  // namespace tracer
