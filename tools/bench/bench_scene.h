// The scene a benchmark program runs: loaded and validated, with the command line's overrides
// applied, and its meshes read.
#pragma once

#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "frontend/load_scene.h"
#include "render/mesh_loader.h"

namespace tracer {

struct BenchScene {
    SceneDescription scene;
    std::vector<TriangleMesh> meshes;
};

// Loads `path`; a non-empty `obj` replaces the first mesh's file, a positive `leaf_size` the
// leaf size. Prints every diagnostic on stderr; nullopt on errors.
inline std::optional<BenchScene> load_bench_scene(const std::string& path, const std::string& obj, int leaf_size) {
    LoadResult loaded = load_scene(path);
    std::optional<std::vector<TriangleMesh>> meshes;
    if (loaded.scene) {
        if (!obj.empty() && !loaded.scene->meshes.empty()) loaded.scene->meshes[0].path = obj;
        if (leaf_size > 0) loaded.scene->render.leaf_size = leaf_size;
        meshes = load_meshes(*loaded.scene, loaded.diagnostics);
    }
    loaded.diagnostics.print(std::cerr);
    if (!loaded.scene || !meshes) return std::nullopt;
    return BenchScene{std::move(*loaded.scene), std::move(*meshes)};
}

}  // namespace tracer
