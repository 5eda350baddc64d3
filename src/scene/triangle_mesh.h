// Triangle meshes as their files hold them, in the file's own coordinates, before any mesh
// block places them: what the file reader hands to the renderer.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace tracer {

struct TriangleMesh {
    std::vector<glm::dvec3> positions;
    std::vector<std::array<uint32_t, 3>> triangles;   // per triangle: indices into positions
    std::vector<glm::dvec3> normals;                  // as the file gives them (not normalised); may be empty
    std::vector<std::array<uint32_t, 3>> normal_ids;  // per triangle: indices into normals; empty
                                                      // unless every triangle has file normals
};

// The meshes of a scene: each file read once, however many mesh blocks name it.
struct SceneMeshes {
    std::vector<TriangleMesh> files;
    std::vector<uint32_t> file_of_block;  // per SceneDescription::meshes entry: index into files
};

}  // namespace tracer
