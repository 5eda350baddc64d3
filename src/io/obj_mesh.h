// Triangle meshes from OBJ files, in the file's own coordinates: polygons triangulated
// (io/polygon.h), zero-area triangles dropped (with a warning), normals kept as the file gives
// them when every face has them. Placing a mesh is the renderer's work.
#pragma once

#include <map>
#include <optional>
#include <string>

#include "base/diagnostics.h"
#include "scene/scene.h"
#include "scene/triangle_mesh.h"

namespace tracer {

// Reads the OBJ file of one mesh block; bad files are reported as `obj-file:line:col: error: ...`.
std::optional<TriangleMesh> load_mesh(const Mesh& mesh, Diagnostics& diagnostics);

// The mesh of OBJ text held in memory (`path` names it in messages); what load_mesh does once
// it has read the file.
std::optional<TriangleMesh> mesh_from_obj_text(const std::string& path, std::string text, Diagnostics& diagnostics);

// Mesh files already read, by normalised path (an animation reads each once for every frame).
using MeshFileCache = std::map<std::string, SharedMesh>;

// Reads the file of every mesh block, each file once however many blocks name it (every bad
// file is reported in one run); a file in `cache` is not read again, one read is added to it.
std::optional<SceneMeshes> load_meshes(const SceneDescription& scene, Diagnostics& diagnostics,
                                       MeshFileCache* cache = nullptr);

}  // namespace tracer
