// Triangle meshes from OBJ files (read by tinyobjloader), placed in the world by the mesh
// block's transform: scale, then rotate, then translate. Polygons are triangulated,
// zero-area triangles dropped (with a warning), and vertex normals taken from the file or,
// when it has none, computed as area-weighted averages of the adjacent face normals.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "frontend/diagnostics.h"
#include "frontend/scene.h"
#include "render/types.h"

namespace tracer {

struct TriangleMesh {
    std::vector<Vec3> positions;                      // world space
    std::vector<Vec3> normals;                        // world space, unit length
    std::vector<std::array<uint32_t, 3>> vertices;    // per triangle: indices into positions
    std::vector<std::array<uint32_t, 3>> normal_ids;  // per triangle: indices into normals
    int material = 0;
};

// Loads one mesh; bad files are reported as `obj-file:line:col: error: ...`.
std::optional<TriangleMesh> load_mesh(const Mesh& mesh, Diagnostics& diagnostics);

// Loads every mesh of the scene (all of them, so every bad file is reported in one run).
std::optional<std::vector<TriangleMesh>> load_meshes(const SceneDescription& scene, Diagnostics& diagnostics);

// Area-weighted vertex normals (zero-area faces add nothing; a vertex with no area gets the
// zero vector, which shading replaces by the face normal).
std::vector<Vec3> area_weighted_normals(const std::vector<Vec3>& positions,
                                        const std::vector<std::array<uint32_t, 3>>& triangles);

}  // namespace tracer
