// Triangle meshes as their files hold them, in the file's own coordinates, before any mesh
// block places them: what the file reader hands to the renderer.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace tracer {

struct TriangleMesh {
    std::vector<glm::dvec3> positions;
    std::vector<std::array<uint32_t, 3>> triangles;   // per triangle: indices into positions
    std::vector<glm::dvec3> normals;                  // as the file gives them (not normalised); may be empty
    std::vector<std::array<uint32_t, 3>> normal_ids;  // per triangle: indices into normals; empty
                                                      // unless every triangle has file normals
    // Surface coordinates (u, v): the file's `vt`, or the flat shape's (flat_shapes.h); empty if none.
    std::vector<glm::dvec2> texcoords;
    std::vector<std::array<uint32_t, 3>> texcoord_ids;  // per triangle: indices into texcoords, or empty
};

// A mesh file as read, shared (by the frames of an animation, which read each file once).
using SharedMesh = std::shared_ptr<const TriangleMesh>;
inline SharedMesh share_mesh(TriangleMesh mesh) {
    return std::make_shared<const TriangleMesh>(std::move(mesh));
}

// The meshes of a scene: each file read once, however many mesh blocks name it.
struct SceneMeshes {
    std::vector<SharedMesh> files;                  // never null
    std::vector<uint32_t> file_of_block;            // per SceneDescription::meshes entry: index into files
    std::vector<uint32_t> file_of_solid_mesh = {};  // per SceneDescription::solid_meshes entry: index into files
};

}  // namespace tracer
