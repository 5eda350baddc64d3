// Reading the mesh statements of an OBJ file (`v`, `vn`, `vt`, `f`) in one pass that checks as it
// reads, so every problem is reported at its line and column and nothing unchecked reaches
// the renderer. Other statements (groups, materials, lines, ...) are skipped. Written here rather than taken from
// tinyobjloader, which the project used first: it counts a face's corners in a byte (a 300-corner polygon came out
// wrong), triangulates large polygons in cubic time, reads "nan" as 0, overflows on an exponent like 1e2147483648,
// splits lines differently from any checker put in front of it, and peaked at ~8x the file
// size in memory.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "base/diagnostics.h"
#include "base/source.h"

namespace tracer {

// Polygons are triangulated by Earcut, whose work grows with the square of a polygon's corners
// when it is self-intersecting (~1e-9 s per corner pair measured): a face may have at most
// kMaxFaceCorners corners, and the faces of 5 or more corners at most kMaxPolygonWork corner
// pairs (n * n summed) in all, so no file can keep the triangulation busy for more than ~30 s.
inline constexpr size_t kMaxFaceCorners = 100000;
inline constexpr double kMaxPolygonWork = 2e10;

// The polygons of an OBJ file with their indices resolved (0-based, every one in range).
struct ObjContents {
    std::vector<glm::dvec3> positions;
    std::vector<glm::dvec3> normals;
    std::vector<glm::dvec2> texcoords;     // (u, v) of each `vt` (a missing v is 0; a w is checked, not used)
    std::vector<uint32_t> face_starts;     // per face: its first corner; one more entry at the end
    std::vector<uint32_t> corner_vertex;   // per corner: index into positions
    std::vector<int32_t> corner_normal;    // per corner: index into normals, or -1 if none
    std::vector<int32_t> corner_texcoord;  // per corner: index into texcoords, or -1 if none
    size_t material_statements = 0;        // usemtl / mtllib lines, which tracer does not use
};

// Reads the mesh statements of `file`; reports every problem found
// (non-finite or out-of-range coordinates, bad or out-of-range indices, binary data) and
// returns nullopt if there was any.
std::optional<ObjContents> read_obj(const SourceFile& file, Diagnostics& diagnostics);

}  // namespace tracer
