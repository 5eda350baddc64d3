// Fuzz target: the OBJ reader and triangulation, then the mesh placed in a world (its BVH
// built) and rendered small, looking at it from outside its bounds.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "fuzz/render_small.h"
#include "io/obj_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace tracer;
    Diagnostics diagnostics;
    auto mesh = mesh_from_obj_text("fuzz.obj", std::string(reinterpret_cast<const char*>(data), size), diagnostics);
    std::ostringstream messages;
    diagnostics.print(messages);
    if (!mesh) return 0;

    // A camera outside the mesh's bounds, when those bounds leave room for one in range.
    glm::dvec3 lower(INFINITY), upper(-INFINITY);
    for (const glm::dvec3& p : mesh->positions) lower = glm::min(lower, p), upper = glm::max(upper, p);
    const glm::dvec3 center = (lower + upper) * 0.5;
    const double extent = std::max({upper.x - lower.x, upper.y - lower.y, upper.z - lower.z, 1e-20});
    if (!(extent < 1e28) || std::abs(center.z) + 3 * extent > 1e29) return 0;
    SceneDescription scene;
    scene.camera.eye = center + glm::dvec3(0, 0, 3 * extent);
    scene.camera.lookat = center;
    scene.materials.push_back({});
    scene.materials.back().kd = glm::dvec3(1.0);
    scene.materials.back().km = glm::dvec3(0.5);
    scene.lights.push_back({scene.camera.eye + glm::dvec3(extent, extent, 0), glm::dvec3(1.0)});
    scene.meshes.push_back({});
    SceneMeshes meshes;
    meshes.files.push_back(share_mesh(std::move(*mesh)));
    meshes.file_of_block.push_back(0);
    render_small(scene, meshes);
    return 0;
}
