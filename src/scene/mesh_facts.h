// What a mesh block puts in the world: its triangle and vertex counts and its bounds once
// placed (for --check, --dump-json and authors standing a mesh on a floor).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
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

// An edge that keeps a mesh from closing: its vertices as the file numbers them (from 1), and
// how many triangles run along it from `from` to `to` and back.
struct UnmatchedEdge {
    uint32_t from = 0, to = 0;
    size_t forward = 0, backward = 0;
};

// The first edge of `mesh` whose triangles do not pair up, each running along it one way with
// one running the other way (vertices at the same point are one vertex); none if the mesh is
// closed and consistently oriented: the boundary of a solid, which CSG needs.
std::optional<UnmatchedEdge> unmatched_edge(const TriangleMesh& mesh);

// "mesh.obj (line 12)": a shape as statistics name it, by its file or kind and its line.
std::string shape_label(const std::string& kind_or_path, int line);

}  // namespace tracer
