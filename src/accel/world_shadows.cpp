// World's queries for many shadow rays from one point (an area light's samples): what a frustum
// of them may meet, and the any-hit search among those candidates alone.
#include "accel/world.h"

#include <algorithm>

namespace tracer {

void World::shadow_candidates(const ShadowFrustum& frustum, const ShadowCandidates* within,
                              ShadowCandidates& out) const {
    out.everything = false;
    out.count = 0;
    out.planes = 0;
    out.unbounded = !unbounded_solids_.empty();
    // Step 1: the planes it crosses.
    if (within && !within->everything) {
        for (uint64_t bits = within->planes; bits; bits &= bits - 1) {
            const int p = __builtin_ctzll(bits);
            if (frustum.may_cross_plane(planes_[size_t(p)].point, planes_[size_t(p)].normal))
                out.planes |= uint64_t(1) << p;
        }
    } else {
        if (planes_.size() > 64) {
            out.everything = true;
            return;
        }
        for (size_t p = 0; p < planes_.size(); ++p)
            if (frustum.may_cross_plane(planes_[p].point, planes_[p].normal)) out.planes |= uint64_t(1) << p;
    }
    // Step 2: the bounded entries, each by its box and the ball around it (a placed mesh's
    // leaves too, by theirs, from `within`'s list of them if it has one).
    auto add = [&](uint32_t entry, const Bounds& box, int within_index) {
        const Bounded& b = bounded_[entry];
        if (!frustum.may_meet_ball(glm::dvec3(b.center), double(b.radius)) || !frustum.may_meet_box(box)) return true;
        if (out.count == ShadowCandidates::kMostEntries) {
            out.everything = true;
            return false;
        }
        out.entries[out.count] = entry;
        out.boxes[out.count] = box;
        add_mesh_leaves(frustum, entry, within_index >= 0 ? within : nullptr, within_index, out);
        ++out.count;
        return true;
    };
    out.leaves_used = 0;
    if (within && !within->everything) {
        for (int i = 0; i < within->count; ++i) add(within->entries[i], within->boxes[i], i);
        return;
    }
    if (linear_) {
        for (uint32_t entry = 0; entry < bounded_.size(); ++entry)
            if (!add(entry, linear_boxes_[entry], -1)) return;
        return;
    }
    top_.leaves_meeting([&](const Bounds& box) { return frustum.may_meet_box(box); },
                        [&](const Bounds& box, uint32_t first, uint32_t count) {
                            const Bounds padded = padded_for_rays(box);
                            for (uint32_t entry = first; entry < first + count; ++entry)
                                if (!add(entry, padded, -1)) return false;
                            return true;
                        });
}

void World::add_mesh_leaves(const ShadowFrustum& frustum, uint32_t entry, const ShadowCandidates* within,
                            int within_index, ShadowCandidates& out) const {
    const int i = out.count;
    out.leaf_first[i] = uint16_t(out.leaves_used);
    out.leaf_count[i] = ShadowCandidates::kWholeMesh;
    const Bounded& b = bounded_[entry];
    if (b.kind != ObjectKind::MeshInstance || !instances_[b.index].placed) return;
    const MeshAccel& mesh = meshes_[instances_[b.index].mesh];
    if (mesh.brute_force()) return;
    auto keep = [&](const TriangleRun& leaf, const Bounds& box) {
        if (!frustum.may_meet_box(box)) return true;
        if (out.leaves_used == ShadowCandidates::kMostLeaves) return false;
        out.leaves[out.leaves_used] = leaf;
        out.leaf_boxes[out.leaves_used++] = box;
        return true;
    };
    bool listed = true;
    if (within) {
        if (within->leaf_count[within_index] == ShadowCandidates::kWholeMesh) return;
        const int first = within->leaf_first[within_index], end = first + within->leaf_count[within_index];
        for (int k = first; k < end && listed; ++k) listed = keep(within->leaves[k], within->leaf_boxes[k]);
    } else {
        listed = mesh.bvh().leaves_meeting([&](const Bounds& box) { return frustum.may_meet_box(box); },
                                           [&](const Bounds& box, uint32_t first, uint32_t count) {
                                               return keep({first, count}, box);
                                           });
    }
    if (!listed) {
        out.leaves_used = out.leaf_first[i];  // too many: the mesh is searched whole
        return;
    }
    out.leaf_count[i] = uint16_t(out.leaves_used - out.leaf_first[i]);
}

bool World::occluded_among(const ShadowCandidates& candidates, const Ray& ray, Interval range, SearchCounts& counts,
                           Occluder& last, uint32_t left_behind) const {
    if (candidates.everything) return occluded(ray, range, counts, last, left_behind);
    // The last blocker first if it is a candidate (and then not again), else forgotten.
    const uint32_t tested = last.entry;
    if (tested != Occluder::kNone) {
        const bool candidate = std::find(candidates.entries, candidates.entries + candidates.count, tested) !=
                               candidates.entries + candidates.count;
        if (candidate && occluder_blocks(last, ray, range, counts, left_behind)) return true;
        last.entry = Occluder::kNone;
    }
    for (uint64_t bits = candidates.planes; bits; bits &= bits - 1) {
        const PlaneShape& p = planes_[size_t(__builtin_ctzll(bits))];
        if (intersect_plane(ray, p.point, p.normal, range)) return true;
    }
    if (candidates.unbounded)
        for (const UnboundedSolid& solid : unbounded_solids_)
            if (solids_.nearest(solid.index, ray, range)) return true;
    for (int i = 0; i < candidates.count; ++i) {
        const uint32_t entry = candidates.entries[i];
        const Bounded& b = bounded_[entry];
        ++counts.objects.primitive_tests;
        if (b.object == left_behind || (entry == tested && b.kind != ObjectKind::MeshInstance)) continue;
        if (b.kind != ObjectKind::Sphere && !ray_may_meet_box(ray, candidates.boxes[i], range)) continue;
        if (candidates.leaf_count[i] != ShadowCandidates::kWholeMesh) {
            const MeshAccel& mesh = meshes_[instances_[b.index].mesh];
            if (mesh.leaves_block(candidates.leaves + candidates.leaf_first[i], candidates.leaf_count[i], ray, range,
                                  counts.triangles, last.triangles)) {
                last.entry = entry;
                return true;
            }
            continue;
        }
        if (bounded_blocks(entry, ray, range, counts, last)) return true;
    }
    return false;
}

World::ConvexBlocker World::convex_blocker(const Occluder& blocker) const {
    if (blocker.entry == Occluder::kNone) return {};
    const Bounded& b = bounded_[blocker.entry];
    switch (b.kind) {
        case ObjectKind::Sphere:
        case ObjectKind::Disc: return {b.object, objects_[b.object].material};
        case ObjectKind::Cone:
            return cones_[b.index].caps ? ConvexBlocker{b.object, objects_[b.object].material} : ConvexBlocker{};
        default: return {};
    }
}

}  // namespace tracer
