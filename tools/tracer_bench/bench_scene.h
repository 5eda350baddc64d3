// The scene a benchmark program runs: loaded and validated, with the command line's overrides
// applied, and its meshes read.
#pragma once

#include <iostream>
#include <optional>
#include <string>

#include "app/load_files.h"

namespace tracer {

// Loads `path`; a non-empty `obj` replaces the first mesh's file, a positive `leaf_size` the
// leaf size. Prints every diagnostic on stderr; nullopt on errors.
inline std::optional<LoadedScene> load_bench_scene(const std::string& path, const std::string& obj, int leaf_size) {
    SceneInput input;
    input.path = path;
    return load_scene_with_meshes(
        input,
        [&](SceneDescription& scene) {
            if (!obj.empty() && !scene.meshes.empty()) scene.meshes[0].path = obj;
            if (leaf_size > 0) scene.render.leaf_size = leaf_size;
        },
        print_diagnostics_to(std::cerr));
}

}  // namespace tracer
