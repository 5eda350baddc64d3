#include "accel/solid_meshes.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <glm/geometric.hpp>

namespace tracer {
namespace {

// The ray's line where it may cross the mesh: from `enter` to `leave` (its box's, on the ray),
// and the ray moved back to `start`, a little before the box, so that every crossing lies at
// t > 0 along `moved` (the triangle test takes no other), at t - start along the ray. The same
// ray always gives the same line: a crossing is found again where it was found first.
struct MeshLine {
    Ray moved;
    Real start = 0, enter = 0, leave = 0;
};

std::optional<MeshLine> mesh_line(const Bounds& box, const Ray& ray, Real tolerance) {
    Real enter = -kInfinity, leave = kInfinity;
    for (int axis = 0; axis < 3; ++axis) {
        const Real d = ray.direction[axis], o = ray.origin[axis];
        if (d == 0) {
            if (o < box.lower[axis] || o > box.upper[axis]) return std::nullopt;
            continue;
        }
        Real t_lower = (box.lower[axis] - o) / d, t_upper = (box.upper[axis] - o) / d;
        if (t_lower > t_upper) std::swap(t_lower, t_upper);
        enter = std::max(enter, t_lower);
        leave = std::min(leave, t_upper);
    }
    if (!(enter <= leave)) return std::nullopt;
    // Half the box's diagonal back: every crossing then lies at least that far along the moved
    // ray, far beyond the roundings of the move (a ray grazing the box's corner, its chord a
    // hair long, lost one crossing of two when moved to just before it), and the moved origin
    // stays as near the mesh as the mesh's size, the roundings of the crossings' t with it.
    const Real start = enter - (glm::length(box.upper - box.lower) / 2 + tolerance);
    return MeshLine{{ray.origin + start * ray.direction, ray.direction}, start, enter, leave};
}

// +1 where the ray goes in through the triangle's front (it faces the ray), -1 where it comes
// out through it, 0 along its plane.
int crossing_sign(const MeshAccel& mesh, const MeshHit& hit, const Vec3& direction) {
    const Triangle t = mesh.triangle(hit.slot);
    const Real facing = glm::dot(glm::cross(t.v1 - t.v0, t.v2 - t.v0), direction);
    return (facing < 0) - (facing > 0);
}

thread_local std::vector<MeshHit> crossings;

}  // namespace

void append_mesh_spans(const MeshAccel& mesh, const Ray& ray, Real until, Real tolerance, uint32_t surface,
                       std::vector<SolidSpan>& out) {
    // Step 1: every crossing from the mesh's box to `until`, in order along the line.
    const std::optional<MeshLine> line = mesh_line(mesh.bounds(), ray, tolerance);
    if (!line) return;
    const Real end = std::min(line->leave, until) + tolerance;
    crossings.clear();
    TraversalCounts counts;
    mesh.all_hits(line->moved, {0, end - line->start}, crossings, counts);
    std::sort(crossings.begin(), crossings.end(), [](const MeshHit& a, const MeshHit& b) { return a.hit.t < b.hit.t; });
    // Step 2: the winding number along the line, a run of crossings closer than the tolerance
    // (one place) stepping it by the sign of their sum; the ray is inside where it is not zero.
    int winding = 0;
    SpanEnd enter;
    for (size_t first = 0; first < crossings.size();) {
        size_t next = first + 1;
        int sum = crossing_sign(mesh, crossings[first], ray.direction);
        for (; next < crossings.size() && crossings[next].hit.t - crossings[next - 1].hit.t <= tolerance; ++next)
            sum += crossing_sign(mesh, crossings[next], ray.direction);
        const int step = (sum > 0) - (sum < 0);
        const Real t = line->start + crossings[first].hit.t;
        first = next;
        if (step == 0) continue;
        const bool was_inside = winding != 0;
        winding += step;
        if (!was_inside)
            enter = {t, surface, false, 0};
        else if (winding == 0)
            out.push_back({enter, {t, surface, false, 1}});
    }
    if (winding != 0) out.push_back({enter, {end + tolerance, surface, false, 1}});  // beyond `until`
}

MeshSurface mesh_span_end_surface(const SolidMesh& mesh, const Ray& ray, Real t, bool leaving, Real tolerance) {
    MeshSurface out;
    RoundSurface& round = out.round;
    const Vec3 outward_if_unknown = leaving ? ray.direction : -ray.direction;
    // Step 1: the triangle at t again, along the same line.
    const std::optional<MeshLine> line = mesh_line(mesh.accel.bounds(), ray, tolerance);
    MeshHit hit;
    TraversalCounts counts;
    Interval range;
    if (line) range = {t - line->start - tolerance, t - line->start + tolerance};
    if (!line || !mesh.accel.intersect(line->moved, range, hit, counts)) {  // not expected: it was found there
        round.point = ray.at(t);
        round.error = gamma(4) * (abs_each(round.point) + abs_each(ray.origin));
        round.normal = out.shading_normal = glm::normalize(outward_if_unknown);
        return out;
    }
    // Step 2: its point, and its normal turned out of the mesh: against the ray where the span
    // enters, along it where it leaves.
    round.point = mesh.accel.surface_point(hit.slot, hit.hit.u, hit.hit.v, round.error);
    round.normal = mesh.accel.geometric_normal(hit.slot);
    if (round.normal == Vec3(0)) round.normal = glm::normalize(outward_if_unknown);  // a sliver
    if ((glm::dot(round.normal, ray.direction) > 0) != leaving) round.normal = -round.normal;
    out.shading_normal = round.normal;
    if (!mesh.flat) {
        const Vec3 shading = mesh.accel.shading_normal(hit.slot, hit.hit.u, hit.hit.v);
        if (shading != Vec3(0)) out.shading_normal = glm::dot(shading, round.normal) < 0 ? -shading : shading;
    }
    return out;
}

}  // namespace tracer
