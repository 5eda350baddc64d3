// Where a mesh block puts its file's triangles: scale, then rotate about the axis, then
// translate, as one affine map in double. Normals map by the inverse transpose.
#pragma once

#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include "render/types.h"
#include "scene/scene.h"

namespace tracer {

struct Placement {
    glm::dmat3 linear{1.0};  // scale, then rotation
    glm::dmat3 normal{1.0};  // inverse transpose of `linear`
    glm::dvec3 translate{0.0};

    Placement() = default;  // the identity: the file's own coordinates
    explicit Placement(const Mesh& mesh) {
        const glm::dmat3 rotation =
            glm::dmat3(glm::rotate(glm::dmat4(1.0), glm::radians(mesh.rotate_degrees), mesh.rotate_axis));
        glm::dmat3 scale(1.0);
        for (int i = 0; i < 3; ++i) scale[i][i] = mesh.scale[i];
        linear = rotation * scale;
        normal = glm::transpose(glm::inverse(linear));
        translate = mesh.translate;
    }

    // A point of the file, placed in the world (in double, whatever Real is).
    glm::dvec3 point(const glm::dvec3& p) const { return linear * p + translate; }
};

}  // namespace tracer
