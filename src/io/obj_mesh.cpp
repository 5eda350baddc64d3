#include "io/obj_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include <glm/geometric.hpp>

#include "base/input_file.h"
#include "io/obj_reader.h"
#include "io/polygon.h"
#include "scene/mesh_facts.h"
#include "scene/placement.h"

namespace tracer {

// Which triangles to keep: every one with an area, and a zero-area one only if its three
// corners are distinct points and each of its edges belongs to another triangle too. Such a
// sliver closes a T-junction of a closed surface (a vertex in the middle of another triangle's
// edge): the watertight triangle test needs it there, or rays slip through the crack that
// rounding opens. Any other zero-area triangle is a line or a point: nothing to hit.
static std::vector<bool> triangles_to_keep(const std::vector<glm::dvec3>& positions,
                                           const std::vector<std::array<uint32_t, 3>>& triangles) {
    std::vector<bool> keep(triangles.size());
    bool any_degenerate = false;
    for (size_t t = 0; t < triangles.size(); ++t) {
        const auto& v = triangles[t];
        const glm::dvec3 cross = glm::cross(positions[v[1]] - positions[v[0]], positions[v[2]] - positions[v[0]]);
        keep[t] = glm::dot(cross, cross) > 0;
        any_degenerate = any_degenerate || !keep[t];
    }
    if (!any_degenerate) return keep;
    std::map<std::pair<uint32_t, uint32_t>, int> edge_uses;
    for (const auto& v : triangles)
        for (int k = 0; k < 3; ++k) ++edge_uses[std::minmax(v[k], v[(k + 1) % 3])];
    for (size_t t = 0; t < triangles.size(); ++t) {
        if (keep[t]) continue;
        const auto& v = triangles[t];
        const bool distinct = positions[v[0]] != positions[v[1]] && positions[v[1]] != positions[v[2]] &&
                              positions[v[0]] != positions[v[2]];
        bool edges_shared = true;
        for (int k = 0; k < 3; ++k) edges_shared = edges_shared && edge_uses[std::minmax(v[k], v[(k + 1) % 3])] >= 2;
        keep[t] = distinct && edges_shared;
    }
    return keep;
}

// After errors in an OBJ file (those kept since `mark`): where the scene names it, as a note
// on the last of them, so that it is printed after that file's errors and nowhere else.
static void note_where_used(const Mesh& mesh, Diagnostics& diagnostics, size_t mark) {
    if (mesh.named_at.line > 0)
        Diagnostics::note(diagnostics.last_error_since(mark), mesh.named_at, "the mesh file is used here");
}

// The triangles of every face, as corner numbers into `obj`'s corner arrays; counts the
// faces that could not be triangulated whole.
static std::vector<std::array<uint32_t, 3>> triangulate_faces(const ObjContents& obj, size_t& broken) {
    std::vector<std::array<uint32_t, 3>> corners;
    corners.reserve(obj.corner_vertex.size());
    std::vector<glm::dvec3> outline;
    std::vector<std::array<uint32_t, 3>> pieces;
    for (size_t face = 0; face + 1 < obj.face_starts.size(); ++face) {
        const uint32_t first = obj.face_starts[face], end = obj.face_starts[face + 1];
        if (end - first == 3) {
            corners.push_back({first, first + 1, first + 2});
            continue;
        }
        outline.clear();
        pieces.clear();
        for (uint32_t c = first; c < end; ++c) outline.push_back(obj.positions[obj.corner_vertex[c]]);
        broken += !triangulate_polygon(outline, pieces);
        for (const auto& piece : pieces) corners.push_back({first + piece[0], first + piece[1], first + piece[2]});
    }
    return corners;
}

std::optional<TriangleMesh> load_mesh(const Mesh& mesh, Diagnostics& diagnostics) {
    const size_t mark = diagnostics.mark();
    InputFile input = read_input_file(mesh.path, kMaxMeshFileBytes);
    if (!input.problem.empty()) {
        diagnostics.report(Severity::Error, Diagnostics::whole_file(mesh.path),
                           "cannot read the mesh file: " + input.problem);
        note_where_used(mesh, diagnostics, mark);
        return std::nullopt;
    }
    auto loaded = mesh_from_obj_text(mesh.path, std::move(input.text), diagnostics);
    if (!loaded) note_where_used(mesh, diagnostics, mark);
    return loaded;
}

std::optional<TriangleMesh> mesh_from_obj_text(const std::string& path, std::string text, Diagnostics& diagnostics) {
    // Step 1: read and check the statements.
    const SourceFile file(path, std::move(text));
    std::optional<ObjContents> obj = read_obj(file, diagnostics);
    if (!obj) return std::nullopt;

    // Step 2: triangles, dropping zero-area ones unless they close a gap.
    size_t broken = 0;
    const std::vector<std::array<uint32_t, 3>> corners = triangulate_faces(*obj, broken);
    std::vector<std::array<uint32_t, 3>> triangles(corners.size());
    for (size_t t = 0; t < corners.size(); ++t)
        for (int k = 0; k < 3; ++k) triangles[t][k] = obj->corner_vertex[corners[t][k]];
    const std::vector<bool> keep = triangles_to_keep(obj->positions, triangles);
    TriangleMesh out;
    bool file_normals = !obj->normals.empty(), file_texcoords = !obj->texcoords.empty();
    size_t degenerate = 0;
    for (size_t t = 0; t < corners.size(); ++t) {
        if (!keep[t]) {
            ++degenerate;
            continue;
        }
        out.triangles.push_back(triangles[t]);
        const auto& c = corners[t];
        const int32_t n0 = obj->corner_normal[c[0]], n1 = obj->corner_normal[c[1]], n2 = obj->corner_normal[c[2]];
        file_normals = file_normals && n0 >= 0 && n1 >= 0 && n2 >= 0;
        if (file_normals) out.normal_ids.push_back({uint32_t(n0), uint32_t(n1), uint32_t(n2)});
        const int32_t t0 = obj->corner_texcoord[c[0]], t1 = obj->corner_texcoord[c[1]], t2 = obj->corner_texcoord[c[2]];
        file_texcoords = file_texcoords && t0 >= 0 && t1 >= 0 && t2 >= 0;
        if (file_texcoords) out.texcoord_ids.push_back({uint32_t(t0), uint32_t(t1), uint32_t(t2)});
    }
    auto warn = [&](size_t count, const std::string& what) {
        if (count > 0)
            diagnostics.report(Severity::Warning, Diagnostics::whole_file(path), std::to_string(count) + what);
    };
    warn(degenerate,
         degenerate == 1 ? " degenerate (zero-area) triangle dropped" : " degenerate (zero-area) triangles dropped");
    warn(broken, broken == 1 ? " self-intersecting polygon could only be triangulated in part"
                             : " self-intersecting polygons could only be triangulated in part");
    warn(obj->material_statements,
         std::string(obj->material_statements == 1 ? " usemtl/mtllib line" : " usemtl/mtllib lines") +
             " ignored: a mesh takes its material from its mesh block");
    if (out.triangles.empty()) {
        diagnostics.report(Severity::Error, Diagnostics::whole_file(path),
                           "the mesh has no triangles (with non-zero area)");
        return std::nullopt;
    }

    // Step 3: the positions, and the file's normals and texture coordinates when every
    // triangle has them.
    out.positions = std::move(obj->positions);
    if (file_normals)
        out.normals = std::move(obj->normals);
    else
        out.normal_ids.clear();
    if (file_texcoords)
        out.texcoords = std::move(obj->texcoords);
    else
        out.texcoord_ids.clear();
    return out;
}

// Reports `mesh`, a part of a solid, if its file is not closed: an error naming an edge.
static bool check_closed(const Mesh& mesh, const TriangleMesh& file, Diagnostics& diagnostics) {
    const std::optional<UnmatchedEdge> edge = unmatched_edge(file);
    if (!edge) return true;
    const std::string name = mesh.path.substr(mesh.path.find_last_of('/') + 1);
    const std::string between =
        "the edge between vertices " + std::to_string(edge->from) + " and " + std::to_string(edge->to) + " of " + name;
    const std::string uses = std::to_string(edge->forward + edge->backward);
    const std::string problem =
        edge->forward + edge->backward == 1 ? between + " has a triangle on one side only: the surface has a hole there"
        : edge->forward == 0 || edge->backward == 0
            ? between + " has " + uses + " triangles all running along it the same way: some face is turned inside out"
            : between + " has " + uses + " triangles that do not pair up (" + std::to_string(edge->forward) +
                  " running one way, " + std::to_string(edge->backward) + " the other)";
    diagnostics.report(Severity::Error, mesh.named_at,
                       "a mesh that is part of a solid must be closed, with an inside: " + problem);
    return false;
}

std::optional<SceneMeshes> load_meshes(const SceneDescription& scene, Diagnostics& diagnostics, MeshFileCache* cache) {
    SceneMeshes meshes;
    std::map<std::string, uint32_t> file_index;  // by normalised absolute path
    bool ok = true;
    // The file of a mesh block, read the first time it is named.
    auto file_of = [&](const Mesh& mesh) {
        const std::string key = std::filesystem::path(mesh.path).lexically_normal().string();
        auto [known, is_new] = file_index.try_emplace(key, uint32_t(meshes.files.size()));
        if (!is_new) return known->second;
        const SharedMesh* read_before = nullptr;
        if (cache)
            if (auto found = cache->find(key); found != cache->end()) read_before = &found->second;
        if (read_before) {
            meshes.files.push_back(*read_before);
        } else if (auto loaded = load_mesh(mesh, diagnostics)) {
            meshes.files.push_back(share_mesh(std::move(*loaded)));
            if (cache) cache->emplace(key, meshes.files.back());
        } else {
            meshes.files.push_back(share_mesh({}));
            ok = false;
        }
        return known->second;
    };
    for (const Mesh& mesh : scene.meshes) meshes.file_of_block.push_back(file_of(mesh));
    for (const Mesh& mesh : scene.solid_meshes) meshes.file_of_solid_mesh.push_back(file_of(mesh));
    if (!ok) return std::nullopt;
    // A part of a solid needs an inside: a closed surface (each file checked once).
    std::vector<bool> checked(meshes.files.size(), false);
    for (size_t part = 0; part < scene.solid_meshes.size(); ++part) {
        const uint32_t file = meshes.file_of_solid_mesh[part];
        if (checked[file]) continue;
        checked[file] = true;
        ok = check_closed(scene.solid_meshes[part], *meshes.files[file], diagnostics) && ok;
    }
    if (!ok) return std::nullopt;
    // A pattern mapped by (u, v) on a file without them sees (0, 0) everywhere: one colour.
    for (size_t block = 0; block < scene.meshes.size(); ++block) {
        const Mesh& mesh = scene.meshes[block];
        if (mesh.material < 0 || !meshes.files[meshes.file_of_block[block]]->texcoord_ids.empty()) continue;
        const Material& material = scene.materials[size_t(mesh.material)];
        if (maps_by_uv(scene.patterns, material.ka_pattern) || maps_by_uv(scene.patterns, material.kd_pattern))
            diagnostics.report(Severity::Warning, mesh.named_at,
                               "this mesh's material maps a pattern by (u, v), but the file gives no texture "
                               "coordinates (vt) for every face: the pattern sees (0, 0) all over it");
    }
    // Placed, no coordinate may leave the renderer's range either: a bound on each block's
    // placed coordinates (scaled, turned, moved) from its file's largest coordinate.
    std::vector<double> largest(meshes.files.size(), 0.0);
    for (size_t f = 0; f < meshes.files.size(); ++f)
        for (const glm::dvec3& p : meshes.files[f]->positions)
            largest[f] = std::max({largest[f], std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    auto check_reach = [&](const Mesh& mesh, uint32_t file) {
        const double reach = Placement(mesh).reach(largest[file]);
        if (const std::string problem = placed_reach_problem("mesh", reach); !problem.empty()) {
            diagnostics.report(Severity::Error, mesh.named_at, problem);
            ok = false;
        }
    };
    for (size_t block = 0; block < scene.meshes.size(); ++block)
        check_reach(scene.meshes[block], meshes.file_of_block[block]);
    for (size_t part = 0; part < scene.solid_meshes.size(); ++part)
        check_reach(scene.solid_meshes[part], meshes.file_of_solid_mesh[part]);
    if (!ok) return std::nullopt;
    return meshes;
}

}  // namespace tracer
