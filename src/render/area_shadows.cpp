#include "render/area_shadows.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "render/light_samples.h"

namespace tracer {
namespace {

// What a sample's shadow ray found.
enum class Seen : uint8_t { Unknown, Lit, Blocked, Through };

// One area light's samples from one hit, their shadow rays classified region by region.
class SampleGrid {
public:
    SampleGrid(const ShadingPoint& point, const Light& light, const LightSamples& samples, const Vec3& origin,
               uint32_t left_behind, Occluder& last, RayCounts& counts)
        : point_(point),
          world_(point.world),
          light_(light),
          samples_(samples),
          origin_(origin),
          left_behind_(left_behind),
          last_(last),
          counts_(counts),
          through_glass_(point.settings.transparent_shadows && point.world.refracts()) {
        thread_local std::vector<Seen> seen;
        thread_local std::vector<uint32_t> blockers;
        thread_local std::vector<Color> through;
        const size_t count = size_t(light.samples());
        seen.assign(count, Seen::Unknown);
        blockers.assign(count, World::ConvexBlocker::kNone);
        if (through_glass_) through.assign(count, Color(0.0));
        seen_ = seen.data(), blockers_ = blockers.data(), through_ = through.data();
        const double n = point.material.n;
        whole_exponent_ = n >= 1 && n <= kMostSquaredExponent && n == std::floor(n);
        exponent_ = whole_exponent_ ? unsigned(n) : 0;
    }

    // Classifies samples [i0, i1] x [j0, j1] (inclusive), `candidates` holding what may block
    // any of their rays.
    void classify(int i0, int i1, int j0, int j1, const ShadowCandidates& candidates) {
        if (cancelled()) return;  // the image is discarded: the rest of the samples stay unknown (unlit)
        if (candidates.empty()) {
            for (int i = i0; i <= i1; ++i)
                for (int j = j0; j <= j1; ++j) mark(i, j, Seen::Lit);
            return;
        }
        if (!samples_.parts_have_hulls() ||
            (i1 - i0 + 1) * (j1 - j0 + 1) <= (light_.adaptive ? kSmallestAdaptiveRegion : kSmallestRegion)) {
            for (int i = i0; i <= i1; ++i)
                for (int j = j0; j <= j1; ++j) test(i, j, candidates);
            return;
        }
        // Step 1: the corners; one convex opaque shape across all four blocks the whole region
        // (where they are the hull's corners; adaptive sampling takes it to wherever they lie).
        // Adaptive sampling also takes a region whose four corners are lit to be lit when every
        // shape that may block it is wider, seen from the point, than the gaps between them.
        const int corner_i[4] = {i0, i1, i1, i0}, corner_j[4] = {j0, j0, j1, j1};
        for (int k = 0; k < 4; ++k) test(corner_i[k], corner_j[k], candidates, true);
        const uint32_t first = blocker(i0, j0);
        bool one_blocker = first != World::ConvexBlocker::kNone && (samples_.corners_are_samples() || light_.adaptive);
        for (int k = 1; k < 4 && one_blocker; ++k) one_blocker = blocker(corner_i[k], corner_j[k]) == first;
        const bool lit = light_.adaptive && all_lit(corner_i, corner_j) && all_wide(i0, i1, j0, j1, candidates);
        if (one_blocker || lit) {
            for (int i = i0; i <= i1; ++i)
                for (int j = j0; j <= j1; ++j) mark(i, j, one_blocker ? Seen::Blocked : Seen::Lit);
            return;
        }
        // Step 2: the two halves across the longer side (each pyramid holds its own samples).
        if (i1 - i0 >= j1 - j0) {
            const int mid = (i0 + i1) / 2;
            part(i0, mid, j0, j1, candidates);
            part(mid + 1, i1, j0, j1, candidates);
        } else {
            const int mid = (j0 + j1) / 2;
            part(i0, i1, j0, mid, candidates);
            part(i0, i1, mid + 1, j1, candidates);
        }
    }

    // Adds the terms of the samples seen (whole or through glass) to `sum`: the sums of
    // max(0, N.L) and max(0, R.V)^n over the samples lit whole, times the share of the colour,
    // and each sample seen through glass with its own factor.
    void add_terms(Color& sum) const {
        thread_local std::vector<Real> n_dot_l, r_dot_v, inverse_distance, along1, along2;
        const int n1 = light_.samples1, n2 = light_.samples2;
        for (auto* row : {&n_dot_l, &r_dot_v, &inverse_distance, &along1, &along2}) row->resize(size_t(n2));
        const Vec3 p = point_.hit.point, normal = point_.normal, viewer = point_.to_viewer;
        const Vec3 e1(samples_.edge1()), e2(samples_.edge2()), centre(light_.position);
        const Real n_dot_v = glm::dot(normal, viewer);
        const bool specular = point_.material.ks != Color(0.0), fades = light_.fade_distance > 0;
        Real diffuse_sum[4] = {0, 0, 0, 0}, specular_sum = 0;
        Color through_sum(0.0);
        for (int i = 0; i < n1; ++i) {
            // Step 1: a row's N.L and R.V = 2 (N.L)(N.V) - L.V, for every sample (vectorised).
            samples_.row(i, along1.data(), along2.data());
            const Real* __restrict a = along1.data();
            const Real* __restrict b = along2.data();
            Real* __restrict cosines = n_dot_l.data();
            Real* __restrict shines = r_dot_v.data();
            Real* __restrict inverses = inverse_distance.data();
            for (int j = 0; j < n2; ++j) {
                const Vec3 offset = (centre + a[j] * e1 - p) + b[j] * e2;
                const Real inverse = 1 / std::sqrt(offset.x * offset.x + offset.y * offset.y + offset.z * offset.z);
                const Real cosine = (normal.x * offset.x + normal.y * offset.y + normal.z * offset.z) * inverse;
                cosines[j] = cosine;
                inverses[j] = inverse;
                shines[j] =
                    2 * cosine * n_dot_v - (viewer.x * offset.x + viewer.y * offset.y + viewer.z * offset.z) * inverse;
            }
            // Step 2: the sums over the row's samples lit whole; those seen through glass apart.
            const Seen* seen = seen_ + index(i, 0);
            for (int j = 0; j < n2; ++j) {
                if (seen[j] == Seen::Blocked) continue;
                const Real fade =
                    fades ? Real(light_attenuation(light_, Vec3(0), 1 / inverse_distance[size_t(j)])) : Real(1);
                const Real diffuse = std::max(Real(0), n_dot_l[size_t(j)]) * fade;
                const Real shine = specular ? Real(power(double(std::max(Real(0), r_dot_v[size_t(j)])))) * fade : 0;
                if (seen[j] == Seen::Lit) {
                    diffuse_sum[j & 3] += diffuse;
                    specular_sum += shine;
                } else if (seen[j] == Seen::Through) {
                    through_sum +=
                        through_[index(i, j)] * (point_.kd * double(diffuse) + point_.material.ks * double(shine));
                }
            }
        }
        const double diffuse = double((diffuse_sum[0] + diffuse_sum[1]) + (diffuse_sum[2] + diffuse_sum[3]));
        const Color lit = point_.kd * diffuse + (specular ? point_.material.ks * double(specular_sum) : Color(0.0));
        sum += share() * (lit + through_sum);
    }

private:
    static constexpr double kMostSquaredExponent = 1024;
    // Regions of this many samples or fewer have each ray tested (adaptive sampling: fewer).
    static constexpr int kSmallestRegion = 32;
    static constexpr int kSmallestAdaptiveRegion = 4;

    // True if the four corners' shadow rays all reached the light.
    bool all_lit(const int (&corner_i)[4], const int (&corner_j)[4]) const {
        for (int k = 0; k < 4; ++k)
            if (seen_[index(corner_i[k], corner_j[k])] != Seen::Lit) return false;
        return true;
    }

    // True if every candidate's box, seen from the origin, is wider than the gaps between the
    // corners' rays at its depth (see `wide`): then, if it fills its box, it cannot pass between
    // them. The object left behind is met by no ray; a box around the origin is never wide;
    // planes are never between (a plane that meets no corner's ray meets none of the region's);
    // a world listed whole may be.
    bool all_wide(int i0, int i1, int j0, int j1, const ShadowCandidates& candidates) const {
        if (candidates.everything || candidates.unbounded) return false;
        glm::dvec3 hull[4];
        samples_.hull(i0, i1, j0, j1, hull);
        const glm::dvec3 origin(origin_), centre = 0.25 * ((hull[0] + hull[1]) + (hull[2] + hull[3]));
        const glm::dvec3 sides[2] = {hull[1] - hull[0], hull[3] - hull[0]};
        const double reach = glm::length(centre - origin);
        const auto wide = [&](const Bounds& box) {
            // Seen across the line of sight, the box's silhouette is the sum of its three edges
            // and the hull a parallelogram of its two sides (scaled to the box's depth). Across
            // each edge of either (where the silhouette is narrowest, or the hull's gaps widest),
            // the silhouette must be wider than the widest gap between the corners there.
            const glm::dvec3 lower(box.lower), upper(box.upper), to_box = 0.5 * (lower + upper) - origin;
            if (glm::all(glm::lessThan(lower, origin)) && glm::all(glm::lessThan(origin, upper))) return false;
            const glm::dvec3 view = glm::normalize(to_box), size = upper - lower;
            const auto across = [&](const glm::dvec3& v) { return v - glm::dot(v, view) * view; };
            const double scale = std::min(1.0, glm::length(to_box) / reach);
            const glm::dvec3 edges[5] = {across({size.x, 0, 0}), across({0, size.y, 0}), across({0, 0, size.z}),
                                         scale * across(sides[0]), scale * across(sides[1])};
            for (const glm::dvec3& edge : edges) {
                const glm::dvec3 normal = glm::cross(view, edge);
                const double length = glm::length(normal);
                if (!(length > 0)) continue;
                const glm::dvec3 w = normal / length;
                const double width =
                    std::abs(glm::dot(w, edges[0])) + std::abs(glm::dot(w, edges[1])) + std::abs(glm::dot(w, edges[2]));
                // The corners along w, in order, and the widest gap between neighbours.
                const double a = glm::dot(w, edges[3]), b = glm::dot(w, edges[4]);
                double at[4] = {0, a, b, a + b};
                std::sort(at, at + 4);
                const double gap = std::max({at[1] - at[0], at[2] - at[1], at[3] - at[2]});
                if (!(width > gap)) return false;  // NaN: not wide
            }
            return true;
        };
        for (int i = 0; i < candidates.count; ++i) {
            if (world_.candidate_object(candidates.entries[i]) == left_behind_) continue;  // no ray meets it
            if (candidates.leaf_count[i] == ShadowCandidates::kWholeMesh) {
                if (!wide(candidates.boxes[i])) return false;
                continue;
            }
            for (int leaf = 0; leaf < candidates.leaf_count[i]; ++leaf)
                if (!wide(candidates.leaf_boxes[candidates.leaf_first[i] + leaf])) return false;
        }
        return true;
    }

    // x^n of the material's exponent n, for x >= 0: by squaring when n is a whole number from 1
    // to kMostSquaredExponent (a relative error of a few ulps: 2 log2(n) roundings), else std::pow.
    double power(double x) const {
        if (!whole_exponent_) return std::pow(x, point_.material.n);
        double result = 1, square = x;
        for (unsigned n = exponent_; n; n >>= 1, square *= square)
            if (n & 1) result *= square;
        return result;
    }

    size_t index(int i, int j) const { return size_t(i) * size_t(light_.samples2) + size_t(j); }
    Color share() const { return light_.color * (1.0 / light_.samples()); }
    uint32_t blocker(int i, int j) const { return blockers_[index(i, j)]; }
    void mark(int i, int j, Seen seen) {
        Seen& s = seen_[index(i, j)];
        if (s == Seen::Unknown) s = seen;
    }
    bool opaque(int material) const { return !through_glass_ || world_.materials()[size_t(material)].kt == Color(0.0); }

    // Classifies the region's samples with the candidates of its own pyramid.
    void part(int i0, int i1, int j0, int j1, const ShadowCandidates& within) {
        glm::dvec3 corners[4];
        samples_.hull(i0, i1, j0, j1, corners);
        ShadowCandidates candidates;
        world_.shadow_candidates(ShadowFrustum(glm::dvec3(origin_), corners), &within, candidates);
        classify(i0, i1, j0, j1, candidates);
    }

    // Traces sample (i, j)'s shadow ray if it has not been, against the candidates; for a
    // region's `corner`, notes the convex shape that blocks it, if one does.
    void test(int i, int j, const ShadowCandidates& candidates, bool corner = false) {
        const size_t k = index(i, j);
        if (seen_[k] != Seen::Unknown) return;
        if (cancelled()) {  // the image is discarded: the rest of the samples are not traced
            seen_[k] = Seen::Blocked;
            return;
        }
        const Vec3 position(samples_.position(i, j));
        const Vec3 light_offset = position - point_.hit.point;
        const Real distance = glm::length(light_offset);
        if (!(distance > 0)) {  // a sample exactly at the point lights nothing there
            seen_[k] = Seen::Blocked;
            return;
        }
        ++counts_.shadow;
        const SpawnedRay shadow = point_.spawn.ray_to(light_offset, distance);
        if (!world_.occluded_among(candidates, shadow.ray, shadow.range, counts_.traversal, last_, left_behind_)) {
            seen_[k] = Seen::Lit;
            return;
        }
        if (corner) {
            const World::ConvexBlocker convex = world_.convex_blocker(last_);
            if (convex.object != World::ConvexBlocker::kNone && opaque(convex.material)) blockers_[k] = convex.object;
        }
        seen_[k] = Seen::Blocked;
        if (through_glass_) {
            through_[k] = light_through(world_, shadow, &position, left_behind_, counts_);
            if (through_[k] != Color(0.0)) seen_[k] = Seen::Through;
        }
    }

    // True once the render is cancelled, looked at before every sample's shadow ray (a light's
    // 65,536 shadow rays, each through up to thousands of glass surfaces, may take minutes).
    bool cancelled() {
        if (!cancelled_ && point_.cancel) cancelled_ = point_.cancel->load(std::memory_order_relaxed);
        return cancelled_;
    }

    const ShadingPoint& point_;
    const World& world_;
    const Light& light_;
    const LightSamples& samples_;
    Vec3 origin_;
    uint32_t left_behind_;
    Occluder& last_;
    RayCounts& counts_;
    bool through_glass_;
    bool whole_exponent_;
    unsigned exponent_;
    Seen* seen_;
    uint32_t* blockers_;
    Color* through_;
    bool cancelled_ = false;
};

// True if every sample's shadow ray leaves from one side of the surface, the one of the light's
// hull's `corners` (by a margin: then the origin and the object left behind are the same for all).
bool one_side(const ShadingPoint& point, const glm::dvec3 (&corners)[4], Vec3& some_offset) {
    int sign = 0;
    for (const glm::dvec3& corner : corners) {
        const Vec3 offset = Vec3(corner) - point.hit.point;
        const Real side = glm::dot(offset, point.hit.geometric_normal);
        if (!(std::abs(side) > Real(1e-6) * glm::length(offset))) return false;
        const int s = side > 0 ? 1 : -1;
        if (sign != 0 && s != sign) return false;
        sign = s;
        some_offset = offset;
    }
    return true;
}

// True if no sample of the light adds anything at the point (as each sample's own term would
// say, with no shadow ray): the light lies wholly behind the shading normal's plane, so every
// N.L <= 0, and no specular term shows (no ks; or an exponent above 0 with the light wholly on
// the viewer's side, L.V >= 0, so that R.V = 2 (N.L)(N.V) - L.V <= 0). Decided at the hull's
// `corners`, by a margin: the samples lie between them.
bool lights_nothing(const ShadingPoint& point, const glm::dvec3 (&corners)[4]) {
    const bool specular = point.material.ks != Color(0.0);
    if (specular && !(point.material.n > 0)) return false;
    for (const glm::dvec3& corner : corners) {
        const Vec3 offset = Vec3(corner) - point.hit.point;
        const Real margin = Real(1e-6) * glm::length(offset);
        if (!(glm::dot(offset, point.normal) < -margin)) return false;
        if (specular && !(glm::dot(offset, point.to_viewer) > margin)) return false;
    }
    return true;
}

}  // namespace

void add_area_light(const ShadingPoint& point, const Light& light, size_t light_index, Occluder& last, Color& sum,
                    RayCounts& counts) {
    const LightSamples samples(light, light_index, point.hit.point);
    const int last_i = light.samples1 - 1, last_j = light.samples2 - 1;
    glm::dvec3 corners[4];
    samples.hull(0, last_i, 0, last_j, corners);
    if (lights_nothing(point, corners)) return;
    const Color share = light.color * (1.0 / light.samples());
    Vec3 offset;
    // Each sample alone: without shadows, under the SPD's rules (their own shadow-ray rule), and
    // for a point that sees the light on both sides of its surface.
    if (!point.settings.shadows || point.settings.spawn_rules == SpawnRules::Spd || !one_side(point, corners, offset)) {
        for (int i = 0; i <= last_i; ++i) {
            if (point.cancel && point.cancel->load(std::memory_order_relaxed)) return;  // the image is discarded
            for (int j = 0; j <= last_j; ++j)
                sum += point_light_term(point, light, Vec3(samples.position(i, j)), share, last, counts);
        }
        return;
    }
    const Vec3 origin = point.spawn.origin(offset);
    const uint32_t left_behind = object_left_behind(point.hit, offset);
    SampleGrid grid(point, light, samples, origin, left_behind, last, counts);
    ShadowCandidates candidates;
    point.world.shadow_candidates(ShadowFrustum(glm::dvec3(origin), corners), nullptr, candidates);
    grid.classify(0, last_i, 0, last_j, candidates);
    grid.add_terms(sum);
}

}  // namespace tracer
