#include "scene/flat_shapes.h"

#include <array>

namespace tracer {
namespace {

// Adds the quad p0 p1 p2 p3 (in winding order) as two triangles sharing the diagonal p0 p2.
void add_quad(TriangleMesh& mesh, uint32_t p0, uint32_t p1, uint32_t p2, uint32_t p3) {
    mesh.triangles.push_back({p0, p1, p2});
    mesh.triangles.push_back({p0, p2, p3});
}

}  // namespace

TriangleMesh triangle_mesh(const FlatTriangle& shape) {
    TriangleMesh mesh;
    mesh.positions = {shape.a, shape.b, shape.c};
    mesh.triangles = {{0, 1, 2}};
    mesh.texcoords = {{0, 0}, {1, 0}, {0, 1}};
    mesh.texcoord_ids = mesh.triangles;
    return mesh;
}

TriangleMesh triangle_mesh(const Quad& shape) {
    TriangleMesh mesh;
    mesh.positions = {shape.corner, shape.corner + shape.edge1, shape.corner + shape.edge1 + shape.edge2,
                      shape.corner + shape.edge2};
    add_quad(mesh, 0, 1, 2, 3);
    mesh.texcoords = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    mesh.texcoord_ids = mesh.triangles;
    return mesh;
}

TriangleMesh triangle_mesh(const Box& shape) {
    TriangleMesh mesh;
    // Corner i takes x from bit 0 of i, y from bit 1, z from bit 2 (0: min, 1: max).
    for (uint32_t i = 0; i < 8; ++i)
        mesh.positions.push_back(
            {(i & 1 ? shape.max : shape.min).x, (i & 2 ? shape.max : shape.min).y, (i & 4 ? shape.max : shape.min).z});
    add_quad(mesh, 0, 4, 6, 2);  // x = min, normal -x
    add_quad(mesh, 1, 3, 7, 5);  // x = max, normal +x
    add_quad(mesh, 0, 1, 5, 4);  // y = min, normal -y
    add_quad(mesh, 2, 6, 7, 3);  // y = max, normal +y
    add_quad(mesh, 0, 2, 3, 1);  // z = min, normal -z
    add_quad(mesh, 4, 5, 7, 6);  // z = max, normal +z
    // Each face's corners' (u, v) from their place in the box (0 at min, 1 at max on each axis).
    using Face = glm::dvec2 (*)(const glm::dvec3& at);
    constexpr Face kFaceCoordinates[] = {
        [](const glm::dvec3& at) { return glm::dvec2(at.z, at.y); },      // -x
        [](const glm::dvec3& at) { return glm::dvec2(1 - at.z, at.y); },  // +x
        [](const glm::dvec3& at) { return glm::dvec2(at.x, at.z); },      // -y
        [](const glm::dvec3& at) { return glm::dvec2(at.x, 1 - at.z); },  // +y
        [](const glm::dvec3& at) { return glm::dvec2(1 - at.x, at.y); },  // -z
        [](const glm::dvec3& at) { return glm::dvec2(at.x, at.y); },      // +z
    };
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        std::array<uint32_t, 3> ids{};
        for (size_t k = 0; k < 3; ++k) {
            const uint32_t i = mesh.triangles[t][k];
            const glm::dvec3 at(i & 1 ? 1 : 0, i & 2 ? 1 : 0, i & 4 ? 1 : 0);
            ids[k] = uint32_t(mesh.texcoords.size());
            mesh.texcoords.push_back(kFaceCoordinates[t / 2](at));
        }
        mesh.texcoord_ids.push_back(ids);
    }
    return mesh;
}

}  // namespace tracer
