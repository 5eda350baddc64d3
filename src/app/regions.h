// Render regions: a window of the frame (--region), and a list of them rendered one after the
// other by one process that loaded the scene once (--region-list, the render farm's workers).
#pragma once

#include <atomic>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "accel/world.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace tracer {

// Why the region {X0, Y0, W, H} does not fit a frame of the render settings' size, or nullopt.
std::optional<std::string> region_problem(const std::vector<int>& region, const RenderSettings& render);

// Why an output path must not be written (checked before its region is rendered), or nullopt.
using OutputCheck = std::function<std::optional<std::string>(const std::string& path)>;

// Reads "X0 Y0 W H OUTPUT" lines from `requests` until it ends, renders each region and writes it
// to OUTPUT (atomically), answering each line on `replies` with "done OUTPUT" or "error OUTPUT:
// message" (flushed). `waiting` is true while it waits for a line. False if interrupted.
bool render_region_list(const World& world, const SceneDescription& scene, RenderOptions options,
                        const OutputCheck& output_problem, std::istream& requests, std::ostream& replies,
                        std::atomic<bool>& waiting);

}  // namespace tracer
