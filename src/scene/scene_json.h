// The resolved scene description as JSON: what `tracer --dump-json` prints and what later
// tools (the Mitsuba converter) read instead of parsing .scn files themselves.
#pragma once

#include <ostream>

#include <nlohmann/json.hpp>

#include "scene/scene.h"
#include "scene/triangle_mesh.h"

namespace tracer {

// Every default filled in; each shape carries its full material; paths are absolute. With the
// scene's meshes as loaded, each mesh block also states its facts (triangles, vertices, placed
// bounds).
nlohmann::ordered_json scene_to_json(const SceneDescription& scene, const SceneMeshes* meshes = nullptr);
// The same document as text (dump(2), invalid UTF-8 replaced, a newline at the end), written
// shape by shape: the memory of one shape's entry, not the whole document's.
void write_scene_json(std::ostream& out, const SceneDescription& scene, const SceneMeshes* meshes = nullptr);

}  // namespace tracer
