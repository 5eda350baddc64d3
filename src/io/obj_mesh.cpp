#include "io/obj_mesh.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <tiny_obj_loader.h>  // TINYOBJLOADER_USE_DOUBLE comes with the CMake target
static_assert(sizeof(tinyobj::real_t) == sizeof(double), "link the double-precision tinyobjloader");

#include <glm/geometric.hpp>

namespace tracer {
namespace {

// tinyobjloader reads "nan" and "inf" as 0 and keeps out-of-range indices, so `v` and `f`
// statements are checked here first, where the line and column are still known.
class ObjChecker {
public:
    ObjChecker(const SourceFile& file, Diagnostics& diagnostics) : file_(file), diagnostics_(diagnostics) {}

    // True if every vertex is finite and every face index names an existing vertex.
    bool check() {
        const std::string_view text = file_.text();
        size_t vertex_total = 0, normal_total = 0;
        for_each_statement(text, [&](std::string_view keyword, std::vector<Token>&) {
            vertex_total += keyword == "v";
            normal_total += keyword == "vn";
        });
        size_t vertices_so_far = 0, normals_so_far = 0;
        for_each_statement(text, [&](std::string_view keyword, std::vector<Token>& tokens) {
            if (keyword == "v" || keyword == "vn") {
                (keyword == "v" ? vertices_so_far : normals_so_far) += 1;
                for (size_t i = 0; i < 3; ++i) {
                    if (i >= tokens.size()) {
                        error(tokens.empty() ? keyword_span_ : tokens.back().span,
                              "'" + std::string(keyword) + "' needs three coordinates");
                        return;
                    }
                    double value = 0;
                    auto [end, status] =
                        std::from_chars(tokens[i].text.data(), tokens[i].text.data() + tokens[i].text.size(), value);
                    bool parsed = status == std::errc() && end == tokens[i].text.data() + tokens[i].text.size();
                    if (!parsed || !std::isfinite(value))
                        error(tokens[i].span,
                              "coordinate '" + std::string(tokens[i].text) + "' is not a finite number");
                    else if (std::abs(value) > kLargestMagnitude)
                        error(tokens[i].span, "coordinate '" + std::string(tokens[i].text) +
                                                  "' lies beyond +-1e30 (the renderer keeps bounding boxes " +
                                                  "in float and squares and cubes lengths)");
                }
            } else if (keyword == "f") {
                if (tokens.size() < 3) error(keyword_span_, "a face needs at least three vertices");
                for (const Token& token : tokens) {
                    // v, v/vt, v/vt/vn or v//vn: check the position and normal indices.
                    std::string_view corner = token.text;
                    size_t slash = corner.find('/');
                    check_index(token, corner.substr(0, slash), vertices_so_far, vertex_total, "vertex", "vertices");
                    size_t second = slash == std::string_view::npos ? slash : corner.find('/', slash + 1);
                    if (second != std::string_view::npos)
                        check_index(token, corner.substr(second + 1), normals_so_far, normal_total, "normal",
                                    "normals");
                }
            }
        });
        return ok_;
    }

private:
    struct Token {
        std::string_view text;
        Span span;
    };

    template <typename Visit>
    void for_each_statement(std::string_view text, Visit visit) {
        size_t pos = 0;
        while (pos < text.size() && !diagnostics_.saturated()) {
            size_t end = text.find('\n', pos);
            if (end == std::string_view::npos) end = text.size();
            std::vector<Token> tokens;
            size_t i = pos;
            while (i < end && text[i] != '#') {
                while (i < end && (text[i] == ' ' || text[i] == '\t' || text[i] == '\r')) ++i;
                size_t start = i;
                while (i < end && text[i] != ' ' && text[i] != '\t' && text[i] != '\r' && text[i] != '#') ++i;
                if (i > start) tokens.push_back({text.substr(start, i - start), {uint32_t(start), uint32_t(i)}});
            }
            if (!tokens.empty()) {
                std::string_view keyword = tokens.front().text;
                keyword_span_ = tokens.front().span;
                tokens.erase(tokens.begin());
                visit(keyword, tokens);
            }
            pos = end + 1;
        }
    }

    void check_index(const Token& token, std::string_view digits, size_t so_far, size_t total, const char* what,
                     const char* plural) {
        if (digits.empty()) return;  // "v//vn" has no texture index; absent normal index
        long index = 0;
        auto [end, status] = std::from_chars(digits.data(), digits.data() + digits.size(), index);
        if (status != std::errc() || end != digits.data() + digits.size()) {
            error(token.span, "'" + std::string(token.text) + "' is not a valid face corner");
            return;
        }
        long resolved = index < 0 ? long(so_far) + index + 1 : index;  // negative: relative to here
        if (index == 0 || resolved < 1 || resolved > long(total))
            error(token.span, std::string(what) + " index " + std::to_string(index) +
                                  " is out of range (the file has " + std::to_string(total) + " " +
                                  (total == 1 ? what : plural) + ")");
    }

    void error(Span span, std::string message) {
        diagnostics_.error(file_, span, std::move(message));
        ok_ = false;
    }

    const SourceFile& file_;
    Diagnostics& diagnostics_;
    Span keyword_span_;
    bool ok_ = true;
};

}  // namespace

// Which triangles to keep: every one with an area, and a zero-area one only if its three
// corners are distinct points and each of its edges belongs to another triangle too. Such a
// sliver closes a T-junction of a closed surface (a vertex in the middle of another triangle's
// edge): the watertight triangle test needs it there, or rays slip through the crack that
// rounding opens. Any other zero-area triangle is a line or a point: nothing to hit.
template <typename Vertices>
static std::vector<bool> triangles_to_keep(const std::vector<glm::dvec3>& positions,
                                           const std::vector<const tinyobj::index_t*>& corners, Vertices vertices) {
    std::vector<bool> keep(corners.size());
    bool any_degenerate = false;
    for (size_t t = 0; t < corners.size(); ++t) {
        const auto v = vertices(corners[t]);
        const glm::dvec3 cross = glm::cross(positions[v[1]] - positions[v[0]], positions[v[2]] - positions[v[0]]);
        keep[t] = glm::dot(cross, cross) > 0;
        any_degenerate = any_degenerate || !keep[t];
    }
    if (!any_degenerate) return keep;
    std::map<std::pair<uint32_t, uint32_t>, int> edge_uses;
    for (const auto* c : corners) {
        const auto v = vertices(c);
        for (int k = 0; k < 3; ++k) ++edge_uses[std::minmax(v[k], v[(k + 1) % 3])];
    }
    for (size_t t = 0; t < corners.size(); ++t) {
        if (keep[t]) continue;
        const auto v = vertices(corners[t]);
        const bool distinct = positions[v[0]] != positions[v[1]] && positions[v[1]] != positions[v[2]] &&
                              positions[v[0]] != positions[v[2]];
        bool edges_shared = true;
        for (int k = 0; k < 3; ++k) edges_shared = edges_shared && edge_uses[std::minmax(v[k], v[(k + 1) % 3])] >= 2;
        keep[t] = distinct && edges_shared;
    }
    return keep;
}

// After errors in an OBJ file: where the scene names it.
static void note_where_used(const Mesh& mesh, Diagnostics& diagnostics) {
    if (mesh.named_at.line > 0) diagnostics.report(Severity::Note, mesh.named_at, "the mesh file is used here");
}

std::optional<TriangleMesh> load_mesh(const Mesh& mesh, Diagnostics& diagnostics) {
    // Step 1: read the text and check what tinyobjloader would let through.
    std::ifstream in(mesh.path, std::ios::binary);
    std::ostringstream buffer;
    buffer << in.rdbuf();
    if (!in) {
        diagnostics.report(Severity::Error, Diagnostics::whole_file(mesh.path), "cannot read the mesh file");
        return std::nullopt;
    }
    const SourceFile file(mesh.path, buffer.str());
    if (!ObjChecker(file, diagnostics).check()) {
        note_where_used(mesh, diagnostics);
        return std::nullopt;
    }

    // Step 2: parse and triangulate.
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromString(std::string(file.text()), "", config)) {
        std::string message = reader.Error();
        while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
        diagnostics.report(Severity::Error, Diagnostics::whole_file(mesh.path), message);
        note_where_used(mesh, diagnostics);
        return std::nullopt;
    }
    const tinyobj::attrib_t& attrib = reader.GetAttrib();

    // Step 3: the vertices and triangles, dropping zero-area ones unless they close a gap.
    TriangleMesh out;
    for (size_t i = 0; i + 2 < attrib.vertices.size(); i += 3)
        out.positions.push_back({attrib.vertices[i], attrib.vertices[i + 1], attrib.vertices[i + 2]});
    std::vector<const tinyobj::index_t*> corners;  // per triangle: its first corner
    for (const tinyobj::shape_t& shape : reader.GetShapes())
        for (size_t i = 0; i + 2 < shape.mesh.indices.size(); i += 3) corners.push_back(&shape.mesh.indices[i]);
    auto vertices = [](const tinyobj::index_t* c) {
        return std::array<uint32_t, 3>{uint32_t(c[0].vertex_index), uint32_t(c[1].vertex_index),
                                       uint32_t(c[2].vertex_index)};
    };
    const std::vector<bool> keep = triangles_to_keep(out.positions, corners, vertices);
    bool file_normals = !attrib.normals.empty();
    size_t degenerate = 0;
    for (size_t t = 0; t < corners.size(); ++t) {
        if (!keep[t]) {
            ++degenerate;
            continue;
        }
        const tinyobj::index_t* c = corners[t];
        out.triangles.push_back(vertices(c));
        file_normals = file_normals && c[0].normal_index >= 0 && c[1].normal_index >= 0 && c[2].normal_index >= 0;
        if (file_normals)
            out.normal_ids.push_back(
                {uint32_t(c[0].normal_index), uint32_t(c[1].normal_index), uint32_t(c[2].normal_index)});
    }
    if (degenerate > 0)
        diagnostics.report(Severity::Warning, Diagnostics::whole_file(mesh.path),
                           std::to_string(degenerate) + " degenerate (zero-area) triangle" +
                               (degenerate == 1 ? "" : "s") + " dropped");
    if (out.triangles.empty()) {
        diagnostics.report(Severity::Error, Diagnostics::whole_file(mesh.path),
                           "the mesh has no triangles (with non-zero area)");
        note_where_used(mesh, diagnostics);
        return std::nullopt;
    }

    // Step 4: the file's normals, when every triangle has them.
    if (file_normals) {
        for (size_t i = 0; i + 2 < attrib.normals.size(); i += 3)
            out.normals.push_back({attrib.normals[i], attrib.normals[i + 1], attrib.normals[i + 2]});
    } else {
        out.normal_ids.clear();
    }
    return out;
}

std::optional<SceneMeshes> load_meshes(const SceneDescription& scene, Diagnostics& diagnostics) {
    SceneMeshes meshes;
    std::map<std::string, uint32_t> file_index;  // by normalised absolute path
    bool ok = true;
    for (const Mesh& mesh : scene.meshes) {
        const std::string key = std::filesystem::path(mesh.path).lexically_normal().string();
        auto [known, is_new] = file_index.try_emplace(key, uint32_t(meshes.files.size()));
        meshes.file_of_block.push_back(known->second);
        if (!is_new) continue;
        if (auto loaded = load_mesh(mesh, diagnostics)) {
            meshes.files.push_back(std::move(*loaded));
        } else {
            meshes.files.emplace_back();
            ok = false;
        }
    }
    if (!ok) return std::nullopt;
    // Placed, no coordinate may leave the renderer's range either: a bound on each block's
    // placed coordinates (scaled, turned, moved) from its file's largest coordinate.
    for (size_t block = 0; block < scene.meshes.size(); ++block) {
        const Mesh& mesh = scene.meshes[block];
        double largest = 0;
        for (const glm::dvec3& p : meshes.files[meshes.file_of_block[block]].positions)
            largest = std::max({largest, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
        const double scale = std::max({mesh.scale.x, mesh.scale.y, mesh.scale.z});
        const double translate =
            std::max({std::abs(mesh.translate.x), std::abs(mesh.translate.y), std::abs(mesh.translate.z)});
        const double reach = std::sqrt(3.0) * scale * largest + translate;
        if (!(reach <= kLargestMagnitude)) {
            char reach_text[32];
            std::snprintf(reach_text, sizeof reach_text, "%.3g", reach);
            diagnostics.report(Severity::Error, mesh.named_at,
                               "this mesh, scaled and moved, reaches coordinates up to " + std::string(reach_text) +
                                   ", beyond +-1e30 (the renderer keeps bounding boxes in float " +
                                   "and squares and cubes lengths)");
            ok = false;
        }
    }
    if (!ok) return std::nullopt;
    return meshes;
}

}  // namespace tracer
