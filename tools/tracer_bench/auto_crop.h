// The benchmarks' hit-dominated crop: the meshes' projected bounding rectangle, padded by 4
// pixels (as embree_bench --crop auto).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "render/camera.h"
#include "render/renderer.h"
#include "scene/placement.h"
#include "scene/scene.h"
#include "scene/triangle_mesh.h"

namespace tracer {

// The pixels that show the meshes, plus 4 on every side, clipped to the image.
inline PixelRect auto_crop(const SceneDescription& scene, const SceneMeshes& meshes) {
    const PinholeCamera camera(scene.camera, scene.render.width, scene.render.height);
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (size_t block = 0; block < scene.meshes.size(); ++block) {
        const Placement placement(scene.meshes[block]);
        for (const auto& p : meshes.files[meshes.file_of_block[block]]->positions) {
            Real x, y;
            if (!camera.project(Vec3(placement.point(p)), x, y)) continue;
            x0 = std::min(x0, double(x)), y0 = std::min(y0, double(y));
            x1 = std::max(x1, double(x)), y1 = std::max(y1, double(y));
        }
    }
    PixelRect crop;
    crop.x0 = std::max(0, int(std::floor(x0)) - 4);
    crop.y0 = std::max(0, int(std::floor(y0)) - 4);
    crop.width = std::min(scene.render.width, int(std::ceil(x1)) + 4) - crop.x0;
    crop.height = std::min(scene.render.height, int(std::ceil(y1)) + 4) - crop.y0;
    return crop;
}

}  // namespace tracer
