// The front end in one call: read a scene file, parse it, validate it.
#pragma once

#include <optional>
#include <string>

#include "base/diagnostics.h"
#include "scene/scene.h"

namespace tracer {

struct LoadResult {
    std::optional<SceneDescription> scene;  // empty when there were errors
    Diagnostics diagnostics;
    bool unreadable = false;                // the scene file itself could not be read
};

// Loads the scene at `path`; every problem found is in the result's diagnostics.
LoadResult load_scene(const std::string& path);

// Parses and validates scene text held in memory (`path` names it in messages and anchors
// relative paths).
LoadResult load_scene_text(const std::string& path, std::string text, bool fragment = false);

}  // namespace tracer
