// The fuzz targets' last stage: a scene rendered at 8 x 8 pixels, one sample, shallow
// recursion, one thread, so every input also goes through the world, the BVHs and shading
// quickly.
#pragma once

#include <algorithm>

#include "accel/world.h"
#include "base/image.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace tracer {

inline void render_small(SceneDescription scene, const SceneMeshes& meshes) {
    scene.render.width = 8;
    scene.render.height = 8;
    scene.render.samples = 1;
    scene.render.max_depth = std::min(scene.render.max_depth, 3);
    const World world(scene, meshes, 1);
    RenderOptions options;
    options.threads = 1;
    Image image;
    RenderStats stats;
    render(world, scene, options, image, stats);
}

}  // namespace tracer
