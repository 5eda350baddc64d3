#include "render/whitted.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "render/direct_light.h"
#include "render/spawn.h"
#include "scene/pattern.h"

namespace tracer {

RayCounts& RayCounts::operator+=(const RayCounts& other) {
    primary += other.primary;
    shadow += other.shadow;
    reflection += other.reflection;
    refraction += other.refraction;
    primary_hits += other.primary_hits;
    total_internal_reflections += other.total_internal_reflections;
    trees_cut += other.trees_cut;
    traversal += other.traversal;
    return *this;
}

// The calling thread's shadow cache for `world`: per light, the shape that blocked its last
// shadow ray (kept between rays; emptied when the thread meets another world).
static std::span<Occluder> shadow_cache(const World& world) {
    thread_local uint64_t serial = 0;
    thread_local std::vector<Occluder> last;
    if (serial != world.serial()) {
        serial = world.serial();
        last.assign(world.lights().size(), Occluder{});
    }
    return last;
}

// A patterned material's ka and kd at a hit (scene/pattern.h): its patterns evaluated at the
// point carried into the shape's own coordinates, and at the surface's (u, v).
[[gnu::noinline]] static void paint(const World& world, const Material& material, const Hit& found,
                                    const SurfaceHit& hit, Color& ka, Color& kd) {
    const glm::dvec3 point = material.to_object(glm::dvec3(hit.point));
    const glm::dvec3 uv_point(
        world.maps_by_uv(hit.material) ? world.surface_uv(found, hit, material.to_object.linear) : glm::dvec2(0.0), 0);
    const std::vector<Pattern>& patterns = world.patterns();
    if (world.ka_scales_kd(hit.material)) {  // `ka 0.1 * squares  kd squares`: the squares once
        const glm::dvec3 unscaled =
            unscaled_pattern_color(patterns, world.images(), material.kd_pattern, point, uv_point);
        ka = patterns[size_t(material.ka_pattern)].multiply * unscaled;
        kd = patterns[size_t(material.kd_pattern)].multiply * unscaled;
        return;
    }
    if (material.ka_pattern >= 0) ka = pattern_color(patterns, world.images(), material.ka_pattern, point, uv_point);
    if (material.kd_pattern >= 0) kd = pattern_color(patterns, world.images(), material.kd_pattern, point, uv_point);
}

// The refracted direction of unit `direction` through a surface whose unit `normal` faces it,
// for eta = n_from / n_to (Snell's law); nullopt on total internal reflection.
static std::optional<Vec3> refracted(const Vec3& direction, const Vec3& normal, Real eta) {
    const Real cos_in = -glm::dot(direction, normal);
    const Real sin2_out = eta * eta * std::max(Real(0), 1 - cos_in * cos_in);
    if (sin2_out > 1) return std::nullopt;
    return glm::normalize(eta * direction + (eta * cos_in - std::sqrt(1 - sin2_out)) * normal);
}

// A refracted ray waiting to be traced, with the product of the weights that lead to it.
struct Branch {
    Ray ray;
    Interval range;
    Color weight;
    int depth;
    uint32_t left_behind;  // the object the ray cannot meet again (object_left_behind)
};

// Refraction makes the ray tree branch: a transmitting surface sends a second, refracted ray.
// Branches wait on a stack (one per thread, kept between rays), traced depth first; a branch
// is dropped if its weight is under kSmallestBranchWeight in every channel (it could change no
// 8-bit pixel by more than a sixteenth of a level) or once a primary ray has spawned
// kMostBranches (pathological scenes, km + kt >= 1 everywhere, would otherwise grow as
// 2^max_depth).
constexpr double kSmallestBranchWeight = 1.0 / 4096;
constexpr int kMostBranches = 4096;

// The calling thread's branch stack, empty (kept between rays: no allocation per ray). Out of
// the way of rays that never refract, which then never touch it.
static std::vector<Branch>& branch_stack() {
    thread_local std::vector<Branch> stack;
    stack.clear();
    return stack;
}

// One ray tree's secondary rays against its bounds (kMostRaysPerTree, kMostBranches) and the
// render's cancel flag, with the refracted branches waiting to be traced.
struct TreeBudget {
    const std::atomic<bool>* cancel;
    std::vector<Branch>* pending = nullptr;  // this thread's stack, once a branch is made
    int spawned = 0;                         // refracted branches
    int tree_rays = 0;                       // reflected and refracted rays
    bool cut = false;                        // a ray refused for the bound

    // One more secondary ray; false when the tree is at its bound or the render is cancelled.
    [[gnu::always_inline]] bool may_spawn() {
        if (tree_rays == kMostRaysPerTree) {
            cut = true;
            return false;
        }
        ++tree_rays;
        return (tree_rays & 255) != 0 || !cancel || !cancel->load(std::memory_order_relaxed);
    }
};

// Step 3 of trace_surfaces at a surface that transmits: the refracted ray, entering if the ray
// meets the front of the surface (its geometric normal faces the ray), pushed as a branch when
// it is visible and the budget allows. Returns what the mirror ray carries: km, and kt too on
// total internal reflection.
[[gnu::always_inline]] static inline Color refract(const Material& material, const SurfaceHit& hit,
                                                   const SpawnPoint& spawn, const Vec3& direction, const Vec3& normal,
                                                   const Color& weight, int depth, bool spd_rules, TreeBudget& budget,
                                                   RayCounts& counts) {
    const bool entering = glm::dot(hit.geometric_normal, direction) < 0;
    const Real eta = Real(entering ? 1 / material.ior : material.ior);
    const Color branch_weight = weight * material.kt;
    const auto refracted_direction = refracted(direction, normal, eta);
    if (!refracted_direction) {
        ++counts.total_internal_reflections;
        return material.km + material.kt;
    }
    const bool visible =
        spd_rules || std::max({branch_weight.r, branch_weight.g, branch_weight.b}) >= kSmallestBranchWeight;
    if (visible && budget.spawned < kMostBranches && budget.may_spawn()) {
        ++counts.refraction, ++budget.spawned;
        const SpawnedRay next = spawn.ray(*refracted_direction);
        if (!budget.pending) budget.pending = &branch_stack();
        budget.pending->push_back(
            {next.ray, next.range, branch_weight, depth + 1, object_left_behind(hit, next.ray.direction)});
    }
    return material.km;
}

// trace() for a ray that may meet a surface. Along a path, colour = local + km *
// trace(reflected) has a single child, so it runs as a loop: `weight` is the product of the
// km of the mirrors passed so far. This keeps any max_depth off the call stack and stops as
// soon as a surface reflects nothing. Refracted rays are further paths (Branch) of their own.
// Compiled twice: without refraction (kRefracts false) it is the single-path loop alone.
// Every secondary ray counts towards kMostRaysPerTree; every 256th looks at `cancel`, as do
// the lights of a hit (direct_light).
// `first_hit`: the primary ray's nearest hit, if already searched for (trace_packet), else null.
template <bool kRefracts>
[[gnu::noinline]] static Color trace_surfaces(const World& world, const RenderSettings& settings, Ray ray,
                                              RayCounts& counts, const std::atomic<bool>* cancel,
                                              const std::optional<Hit>* first_hit = nullptr) {
    Color color(0.0);
    const bool spd_rules = settings.spawn_rules == SpawnRules::Spd;
    const std::span<Occluder> last_blockers = shadow_cache(world);
    TreeBudget budget{cancel};
    Branch path{ray, kPrimaryRange, Color(1.0), 0, kNoObject};
    for (;;) {
        Color weight = path.weight;
        Interval range = path.range;
        uint32_t left_behind = path.left_behind;
        ray = path.ray;
        for (int depth = path.depth;; ++depth) {
            // Step 1: the nearest surface, or the background.
            const auto found = first_hit ? *std::exchange(first_hit, nullptr)
                                         : world.nearest_hit(ray, range, counts.traversal, left_behind);
            if (!found) {
                color += weight * settings.background;
                break;
            }
            if (depth == 0) ++counts.primary_hits;
            // Built in place: through a std::optional the record was copied by wide loads of
            // narrower stores just made, which stall (docs/bench/code-figures.md).
            const SurfaceHit hit = world.surface(ray, *found);

            // Step 2: local Phong shading with the normal facing the incoming ray.
            const Material& material = world.materials()[size_t(hit.material)];
            const Vec3 normal = glm::dot(hit.normal, ray.direction) > 0 ? -hit.normal : hit.normal;
            const Vec3 to_viewer = -ray.direction;
            const SpawnPoint spawn(hit);
            Color ka = material.ka, kd = material.kd;
            if (material.patterned()) [[unlikely]]
                paint(world, material, *found, hit, ka, kd);
            const ShadingPoint lit{world, settings, material, kd, hit, spawn, normal, to_viewer, cancel};
            color += weight * (ka + direct_light(lit, last_blockers, counts));
            if (depth == settings.max_depth) break;

            // Step 3: the refracted ray, a branch of its own; on total internal reflection, kt joins km.
            const Color reflect =
                kRefracts && material.kt != Color(0.0)
                    ? refract(material, hit, spawn, ray.direction, normal, weight, depth, spd_rules, budget, counts)
                    : material.km;

            // Step 4: continue along the mirror direction D - 2(D.N)N (the SPD's rules: from every
            // surface with km or kt, whatever the path's weight).
            weight *= reflect;
            if (spd_rules ? material.km == Color(0.0) && material.kt == Color(0.0) : weight == Color(0.0)) break;
            if (!budget.may_spawn()) {
                counts.trees_cut += budget.cut;
                return color;  // the rest of the tree, pending branches included, returns black
            }
            ++counts.reflection;
            const SpawnedRay reflected = spawn.ray(ray.direction - 2 * glm::dot(ray.direction, normal) * normal);
            ray = reflected.ray;
            range = reflected.range;
            left_behind = object_left_behind(hit, ray.direction);
        }
        if (!kRefracts || !budget.pending || budget.pending->empty()) {
            counts.trees_cut += budget.cut;
            return color;
        }
        path = budget.pending->back();
        budget.pending->pop_back();
    }
}

// A ray that can meet nothing (most of a frame around a lone mesh) returns the background
// here, without the set-up of the nearest-hit search, which trace_surfaces keeps out of line
// (docs/bench/code-figures.md).
Color trace(const World& world, const RenderSettings& settings, Ray ray, RayCounts& counts,
            const std::atomic<bool>* cancel) {
    ++counts.primary;
    if (!world.may_hit(ray)) return settings.background;
    return world.refracts() ? trace_surfaces<true>(world, settings, ray, counts, cancel)
                            : trace_surfaces<false>(world, settings, ray, counts, cancel);
}

void trace_packet(const World& world, const RenderSettings& settings, const Ray* const* rays, int count, Color* out,
                  RayCounts& counts, const std::atomic<bool>* cancel) {
    if (!world.packet_shares_a_mesh(rays, count)) {
        for (int i = 0; i < count; ++i) out[i] = trace(world, settings, *rays[i], counts, cancel);
        return;
    }
    counts.primary += uint64_t(count);
    const Ray* hitting[kPacket];
    int pixel[kPacket];
    int n = 0;
    for (int i = 0; i < count; ++i) {
        if (world.may_hit(*rays[i])) {
            hitting[n] = rays[i];
            pixel[n++] = i;
        } else {
            out[i] = settings.background;
        }
    }
    if (n == 0) return;
    std::optional<Hit> first[kPacket];
    world.nearest_hits(hitting, n, kPrimaryRange, first, counts.traversal);
    for (int k = 0; k < n; ++k)
        out[pixel[k]] = world.refracts()
                            ? trace_surfaces<true>(world, settings, *hitting[k], counts, cancel, &first[k])
                            : trace_surfaces<false>(world, settings, *hitting[k], counts, cancel, &first[k]);
}

}  // namespace tracer
