// World::surface_uv: the (u, v) of a hit on each kind of shape, as docs/guide/patterns.md draws
// them. Round shapes and planes take them from where the hit lies in the shape's own
// coordinates, around an axis: a sphere's is its own y, a cone's runs from its base to its top,
// a disc's and a plane's is their normal. The axis stands in for y after the shortest rotation
// that takes y to it (the half turn about x if it points down y), which carries x and z along.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "accel/world.h"
#include "scene/pattern.h"

namespace tracer {
namespace {

using dvec2 = glm::dvec2;

// `v` turned by the shortest rotation that takes (0, 1, 0) to unit `axis`.
dvec3 turned_from_y(const dvec3& axis, const dvec3& v) {
    const double c = axis.y;  // cos of the angle between y and the axis
    if (c <= -1 + 1e-12) return {v.x, -v.y, -v.z};
    const dvec3 k(axis.z, 0, -axis.x);  // y x axis
    return v * c + glm::cross(k, v) + k * (glm::dot(k, v) / (1 + c));
}

// The coordinates of `d` in the frame around unit `axis`: (x, along the axis, z).
dvec3 around(const dvec3& axis, const dvec3& d) {
    return {glm::dot(d, turned_from_y(axis, {1, 0, 0})), glm::dot(d, axis),
            glm::dot(d, turned_from_y(axis, {0, 0, 1}))};
}

// The angle around the axis, 0..1, 0.5 towards z and rising towards x (as spherical mapping's u).
double turn(const dvec3& local) {
    return 0.5 + std::atan2(local.x, local.z) / (2 * std::numbers::pi);
}

// A disc's (or cap's) (u, v): its square of side 2 r, seen from its front with -z up.
dvec2 across_disc(const dvec3& local, double radius) {
    return {(1 + local.x / radius) / 2, (1 - local.z / radius) / 2};
}

dvec3 unit(const dvec3& v) {
    const double length = glm::length(v);
    return length > 0 ? v / length : dvec3(0, 1, 0);
}

}  // namespace

glm::dvec2 World::surface_uv(const Hit& hit, const SurfaceHit& surface, const glm::dmat3& to_object) const {
    const Object& object = objects_[hit.object];
    const dvec3 point(surface.point);
    switch (object.kind) {
        case ObjectKind::Sphere: {
            const glm::dvec3 uv =
                mapped(Mapping::Spherical, to_object * (point - dvec3(bounded_[object.index].center)));
            return {uv.x, uv.y};
        }
        case ObjectKind::Plane: {
            // Normals map by the inverse transpose: the plane's own normal is to_object^-T n.
            const PlaneShape& plane = planes_[object.index];
            const dvec3 normal = unit(glm::transpose(glm::inverse(to_object)) * dvec3(plane.normal));
            const dvec3 local = around(normal, to_object * (point - dvec3(plane.point)));
            return {local.x, -local.z};
        }
        case ObjectKind::Disc: {
            const DiscShape& disc = discs_[object.index];
            const double scale = glm::length(to_object[0]);  // a disc is placed by one factor
            const dvec3 local = around(unit(to_object * dvec3(disc.normal)), to_object * (point - dvec3(disc.center)));
            return across_disc(local, double(disc.radius) * scale);
        }
        case ObjectKind::Cone: {
            if (cone_ends_.empty()) return {0, 0};
            const Cone& cone = cone_ends_[object.index];
            const double scale = glm::length(to_object[0]);
            const dvec3 axis = to_object * (cone.top - cone.base);
            const double height = glm::length(axis);
            const dvec3 local = around(axis / height, to_object * (point - cone.base));
            if (hit.primitive == kConeSide) return {turn(local), std::clamp(local.y / height, 0.0, 1.0)};
            // A cap: the tip's is the narrow end's, at the base unless the top is narrower.
            const bool top_is_narrow = cone.top_radius < cone.base_radius;
            const bool at_top = (hit.primitive == kConeTipCap) == top_is_narrow;
            return across_disc(local, (at_top ? cone.top_radius : cone.base_radius) * scale);
        }
        case ObjectKind::MeshInstance:
            return meshes_[instances_[object.index].mesh].surface_uv(hit.primitive, hit.u, hit.v);
        case ObjectKind::Solid: return {0, 0};  // not yet: a solid's patterns map by 3D coordinates
    }
    return {0, 0};
}

}  // namespace tracer
