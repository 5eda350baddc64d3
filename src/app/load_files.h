// Everything a render needs from disk in one call: the scene file (read, parsed, validated),
// adjusted by the caller (command-line overrides), and the OBJ files of its meshes.
#pragma once

#include <functional>
#include <iosfwd>
#include <optional>
#include <string>

#include "lang/interpreter.h"
#include "scene/scene.h"
#include "scene/triangle_mesh.h"

namespace tracer {

struct LoadedScene {
    SceneDescription scene;
    SceneMeshes meshes;
};

// Loads the scene at `path`, lets `adjust` change it before its meshes are read, and prints
// every diagnostic on `errors`. nullopt on errors, with `unreadable` set (if given) when the
// scene file itself could not be read.
std::optional<LoadedScene> load_scene_with_meshes(const std::string& path,
                                                  const std::function<void(SceneDescription&)>& adjust,
                                                  std::ostream& errors, bool* unreadable = nullptr,
                                                  const ParameterValues& parameters = {});

}  // namespace tracer
