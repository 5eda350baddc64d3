// What a mesh block puts in the world: its triangle and vertex counts and its bounds once
// placed (for --check, --dump-json and authors standing a mesh on a floor).
#pragma once

#include <cstddef>
#include <string>

#include "scene/scene.h"
#include "scene/triangle_mesh.h"

namespace tracer {

struct MeshFacts {
    size_t triangles = 0;
    size_t vertices = 0;  // the file's vertices that some triangle uses
    dvec3 lower{0.0};     // the placed vertices' box (zero when there are none)
    dvec3 upper{0.0};
};

// The facts of `mesh` placed by `placed`, computed in double.
MeshFacts mesh_facts(const TriangleMesh& mesh, const Placed& placed);

// "mesh.obj (line 12)": a shape as statistics name it, by its file or kind and its line.
std::string shape_label(const std::string& kind_or_path, int line);

}  // namespace tracer
