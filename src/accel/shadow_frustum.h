// The pyramid of shadow rays from one point to the samples of an area light: every segment from
// the apex to a point of a convex quadrilateral (the samples' hull on the light). Shapes whose
// box lies outside it cannot block any of those rays, which is what lets an area light's
// shadow rays skip most of the world together (World::shadow_candidates). The tests are
// conservative: a box is ruled out only when it lies beyond a face by more than rounding can
// explain, so "outside" is certain and "may meet" is all that is said otherwise.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "accel/bvh_search.h"
#include "accel/mesh_accel.h"
#include "accel/types.h"

namespace tracer {

class ShadowFrustum {
public:
    // The pyramid from `apex` to the quadrilateral corners[0..4), given in order around it.
    ShadowFrustum(const glm::dvec3& apex, const glm::dvec3 (&corners)[4]) : apex_(apex) {
        double scale = max_abs(apex);
        for (int k = 0; k < 4; ++k) corners_[k] = corners[k], scale = std::max(scale, max_abs(corners[k]));
        scale_ = scale;
        // A side through the apex and two neighbouring corners, turned so that the corner after
        // them lies on its inner (negative) side; a side that cannot be turned (a light of one
        // sample along an edge, an apex in the light's plane) is left out: it rules nothing out.
        // (Squared lengths throughout: no square root.)
        for (int k = 0; k < 4; ++k) {
            const glm::dvec3 a = corners[k] - apex, b = corners[(k + 1) % 4] - apex;
            const glm::dvec3 n = glm::cross(a, b), other = corners[(k + 2) % 4] - apex;
            const double side = glm::dot(n, other);
            if (!(side * side > kFlat * glm::dot(n, n) * glm::dot(other, other))) continue;
            sides_[side_count_++] = {side > 0 ? -n : n, glm::dot(n, n)};
        }
        // The light's plane, its normal turned away from the apex (the rays end before it), and the
        // plane through the apex beside it (they start after it).
        const glm::dvec3 n = glm::cross(corners[1] - corners[0], corners[3] - corners[0]), to_apex = apex - corners[0];
        const double apex_side = glm::dot(n, to_apex);
        if (apex_side * apex_side > kFlat * glm::dot(n, n) * glm::dot(to_apex, to_apex)) {
            far_ = {apex_side > 0 ? -n : n, glm::dot(n, n)};
            near_ = {-far_.normal, far_.length2};  // through the apex: the rays start there
            far_point_ = corners[0];
            has_far_ = true;
        }
    }

    // False if no point of `box` lies in the pyramid (within rounding).
    bool may_meet_box(const Bounds& box) const {
        const glm::dvec3 lower(box.lower), upper(box.upper);
        const double tolerance = kRelativeTolerance * (scale_ + std::max(max_abs(lower), max_abs(upper)));
        for (int k = 0; k < side_count_; ++k)
            if (outside(sides_[k], apex_, lower, upper, tolerance)) return false;
        if (!has_far_) return true;
        return !outside(far_, far_point_, lower, upper, tolerance) && !outside(near_, apex_, lower, upper, tolerance);
    }

    // False if no point of the ball lies in the pyramid (within rounding).
    bool may_meet_ball(const glm::dvec3& center, double radius) const {
        const double reach = radius + kRelativeTolerance * (scale_ + max_abs(center) + radius);
        for (int k = 0; k < side_count_; ++k)
            if (beyond(sides_[k], glm::dot(sides_[k].normal, center - apex_), reach)) return false;
        if (!has_far_) return true;
        return !beyond(far_, glm::dot(far_.normal, center - far_point_), reach) &&
               !beyond(near_, glm::dot(near_.normal, center - apex_), reach);
    }

    // False if no ray of the pyramid can meet the plane through `point` with unit `normal` (as
    // intersect_plane tests it from an origin at the apex): the apex lies in the plane (every
    // ray meets it at t = 0, which no search counts), or on one side of it with every corner on
    // that side by more than rounding.
    bool may_cross_plane(const Vec3& point, const Vec3& normal) const {
        const Real numerator = glm::dot(point - Vec3(apex_), normal);  // intersect_plane's, for this origin
        if (numerator == 0) return false;
        if (numerator != numerator) return true;
        const double sign = numerator < 0 ? 1 : -1;  // the apex's side
        const glm::dvec3 p(point), n(normal);
        const double tolerance = kRelativeTolerance * (scale_ + max_abs(p));
        for (const glm::dvec3& corner : corners_)
            if (!(glm::dot(n, corner - p) * sign > tolerance)) return true;
        return false;
    }

private:
    struct Face {
        glm::dvec3 normal;  // outwards, of any length
        double length2;     // of `normal`, squared
    };
    // Sizes below this fraction of the coordinates involved are rounding, not distance.
    static constexpr double kRelativeTolerance = 1e-7;
    // A face whose sine (squared) of the angle with a third corner is below this is flat.
    static constexpr double kFlat = 1e-18;

    static double max_abs(const glm::dvec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }
    // True if `signed_distance` (times the normal's length) lies beyond `reach` of the face.
    static bool beyond(const Face& face, double signed_distance, double reach) {
        return signed_distance > 0 && signed_distance * signed_distance > reach * reach * face.length2;
    }
    // True if the whole box lies beyond the face through `point` by more than `tolerance`.
    static bool outside(const Face& face, const glm::dvec3& point, const glm::dvec3& lower, const glm::dvec3& upper,
                        double tolerance) {
        const glm::dvec3 nearest(face.normal.x > 0 ? lower.x : upper.x, face.normal.y > 0 ? lower.y : upper.y,
                                 face.normal.z > 0 ? lower.z : upper.z);
        return beyond(face, glm::dot(face.normal, nearest - point), tolerance);
    }

    glm::dvec3 apex_;
    glm::dvec3 corners_[4];
    double scale_ = 0;
    Face sides_[4];
    int side_count_ = 0;
    Face far_{}, near_{};
    glm::dvec3 far_point_{0.0};
    bool has_far_ = false;
};

// What may block some ray of a ShadowFrustum: entries of the world's top level and planes
// (World::shadow_candidates), or everything when they are too many to list. A mesh built placed
// may list the leaves of its BVH that meet the frustum, when they are few: then only their
// triangles are tested.
struct ShadowCandidates {
    static constexpr int kMostEntries = 32;
    static constexpr int kMostLeaves = 48;
    static constexpr uint16_t kWholeMesh = 0xffff;  // leaf_count of an entry searched whole
    bool everything = false;
    int count = 0;
    uint32_t entries[kMostEntries];
    Bounds boxes[kMostEntries];  // around each entry (its leaf's box in a BVH)
    // An entry's leaves: leaves[leaf_first[i] .. + leaf_count[i]), or kWholeMesh (any entry
    // not a placed mesh, or one whose leaves are too many).
    uint16_t leaf_first[kMostEntries], leaf_count[kMostEntries];
    int leaves_used = 0;
    TriangleRun leaves[kMostLeaves];
    Bounds leaf_boxes[kMostLeaves];
    uint64_t planes = 0;     // bit p: plane p (the first 64; more make `everything`)
    bool unbounded = false;  // the world's unbounded solids (always listed: they have no box)

    bool empty() const { return !everything && count == 0 && planes == 0 && !unbounded; }
};

}  // namespace tracer
