#include "accel/mesh_accel.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <new>
#include <optional>
#include <type_traits>

#include <glm/geometric.hpp>

#include "accel/ray_packet.h"
#include "base/parallel.h"
#include "base/portable.h"

namespace tracer {

std::vector<Vec3> area_weighted_normals(std::span<const Vec3> positions,
                                        const std::vector<std::array<uint32_t, 3>>& triangles) {
    std::vector<Vec3> sums(positions.size(), Vec3(0));
    for (const auto& t : triangles) {
        // The unnormalised cross product is the face normal times twice the area.
        const Vec3 weighted = glm::cross(positions[t[1]] - positions[t[0]], positions[t[2]] - positions[t[0]]);
        for (uint32_t v : t) sums[v] += weighted;
    }
    for (Vec3& n : sums) n = normalize_or_zero(n);
    return sums;
}

namespace {

// Triangles with their second and third corners swapped: a mirrored file's winding, turning
// again the way its (mirrored) normals point.
std::vector<std::array<uint32_t, 3>> reversed_winding(std::vector<std::array<uint32_t, 3>> triangles) {
    for (auto& t : triangles) std::swap(t[1], t[2]);
    return triangles;
}

// Frees a vector's storage now.
template <typename T>
void release(std::vector<T>& v) {
    std::vector<T>().swap(v);
}

}  // namespace

void PlacedTriangles::reserve_more(size_t more_positions, size_t more_normals, size_t more_triangles) {
    positions.reserve(positions.size() + more_positions);
    normals.reserve(normals.size() + more_normals);
    triangles.reserve(triangles.size() + more_triangles);
    if (more_normals > 0 || !normal_ids.empty()) normal_ids.reserve(normal_ids.size() + more_triangles);
    for (auto* per_triangle : {&tags, &numbers}) per_triangle->reserve(per_triangle->size() + more_triangles);
}

void append_part(PlacedTriangles& out, const MeshPart& part, int threads) {
    const TriangleMesh& file = *part.file;
    const Placement& placement = part.placement;
    const bool mirrored = placement.mirrors();
    const auto reversed = mirrored ? reversed_winding(file.triangles) : std::vector<std::array<uint32_t, 3>>{};
    const auto& corners = mirrored ? reversed : file.triangles;
    const uint32_t first_position = uint32_t(out.positions.size()), first_normal = uint32_t(out.normals.size());
    out.positions.resize(first_position + file.positions.size());
    parallel_for(
        file.positions.size(),
        [&](size_t i) { out.positions[first_position + i] = Vec3(placement.point(file.positions[i])); }, threads);
    // Normals: none for flat (each triangle's face normal, worked out from the corners when
    // shading), the file's placed by the inverse transpose, else area-weighted over the placed
    // triangles.
    if (part.flat) {
        // nothing stored
    } else if (!file.normal_ids.empty()) {
        out.normals.resize(first_normal + file.normals.size());
        parallel_for(
            file.normals.size(),
            [&](size_t i) {
                out.normals[first_normal + i] = normalize_or_zero(Vec3(placement.normal * file.normals[i]));
            },
            threads);
    } else {
        const std::vector<Vec3> normals =
            area_weighted_normals(std::span(out.positions).subspan(first_position), corners);
        out.normals.insert(out.normals.end(), normals.begin(), normals.end());
    }
    const auto reversed_ids = mirrored ? reversed_winding(file.normal_ids) : std::vector<std::array<uint32_t, 3>>{};
    const auto& ids = file.normal_ids.empty() ? corners : mirrored ? reversed_ids : file.normal_ids;
    // Normal ids are kept from the first smooth part on (the flat triangles before it get kFlat):
    // a mesh of flat shapes alone has none (12 bytes a triangle).
    constexpr std::array kAllFlat{PlacedTriangles::kFlat, PlacedTriangles::kFlat, PlacedTriangles::kFlat};
    const bool keep_ids = !part.flat || !out.normal_ids.empty();
    if (keep_ids) out.normal_ids.resize(out.triangles.size(), kAllFlat);
    for (uint32_t t = 0; t < corners.size(); ++t) {
        const auto& v = corners[t];
        const auto& n = ids[t];
        out.triangles.push_back({first_position + v[0], first_position + v[1], first_position + v[2]});
        if (keep_ids)
            out.normal_ids.push_back(
                part.flat ? kAllFlat : std::array{first_normal + n[0], first_normal + n[1], first_normal + n[2]});
        out.tags.push_back(part.tag);
        out.numbers.push_back(t);
    }
    // Surface coordinates, their corners in the order just stored (swapped with them if mirrored).
    if (out.keep_uvs) {
        const bool known = file.texcoord_ids.size() == file.triangles.size();
        for (size_t t = 0; t < file.triangles.size(); ++t) {
            std::array<glm::vec2, 3> uv{};
            if (known)
                for (size_t k = 0; k < 3; ++k) uv[k] = glm::vec2(file.texcoords[file.texcoord_ids[t][k]]);
            if (mirrored) std::swap(uv[1], uv[2]);
            out.uvs.push_back(uv);
        }
    }
}

PlacedTriangles place(const std::vector<MeshPart>& parts, int threads, size_t flat_positions, size_t flat_triangles,
                      bool keep_uvs) {
    PlacedTriangles mesh;
    mesh.keep_uvs = keep_uvs;
    size_t positions = flat_positions, normals = 0, triangles = flat_triangles;
    for (const MeshPart& part : parts) {
        positions += part.file->positions.size();
        triangles += part.file->triangles.size();
        normals += part.flat                       ? 0
                   : part.file->normal_ids.empty() ? part.file->positions.size()
                                                   : part.file->normals.size();
    }
    mesh.reserve_more(positions, normals, triangles);
    for (const MeshPart& part : parts) append_part(mesh, part, threads);
    return mesh;
}

std::vector<uint32_t> small_shapes(const std::vector<uint32_t>& tags) {
    // Runs of one tag: a run of at most kMostShapeTriangles is a shape, a longer one (a mesh
    // block's) gives a shape per triangle.
    std::vector<uint32_t> first_of_shape;
    for (size_t run = 0; run < tags.size();) {
        size_t end = run + 1;
        while (end < tags.size() && tags[end] == tags[run]) ++end;
        if (end - run <= kMostShapeTriangles)
            first_of_shape.push_back(uint32_t(run));
        else
            for (size_t t = run; t < end; ++t) first_of_shape.push_back(uint32_t(t));
        run = end;
    }
    if (first_of_shape.size() * 2 > tags.size()) return {};  // not worth it
    first_of_shape.push_back(uint32_t(tags.size()));
    return first_of_shape;
}

// Placing is loading, as reading the file is: not in build_seconds, which times what Embree's
// build does.
MeshAccel::MeshAccel(const std::vector<MeshPart>& parts, const SearchSettings& settings)
    : MeshAccel(place(parts, settings.threads, 0, 0, settings.keep_uvs), settings) {}

MeshAccel::MeshAccel(PlacedTriangles&& mesh, const SearchSettings& settings) : brute_force_(settings.brute_force) {
    const size_t n = mesh.triangles.size();
    const auto start = std::chrono::steady_clock::now();

    // Step 1: small shapes (a box's twelve triangles, a quad's two) as one primitive each of the
    // BVH's build, where that at least halves its primitives; its leaves then hold whole shapes.
    const std::vector<uint32_t> first_of_shape =
        brute_force_ || settings.build != BvhBuild::Sah || mesh.tags.size() != n ? std::vector<uint32_t>{}
                                                                                 : small_shapes(mesh.tags);

    // Step 2: the accelerator over the primitives' bounds, and the leaf order.
    build_tree(mesh, first_of_shape, settings);

    // Step 3: the triangles in that order; then their hit records (each input freed once read,
    // the BVH's leaf order too: the hit records keep each slot's triangle number).
    triangle_count_ = n;
    const std::vector<uint32_t> order = brute_force_ ? std::vector<uint32_t>{} : bvh_.take_order();
    store_triangles(mesh, order, settings.threads);
    store_hit_records(mesh, order, settings.threads);
    size_t leaves = 0;
    bvh_.for_each_leaf([&](const Bounds&, uint32_t first, uint32_t count, int) {
        ++leaves;
        one_leaf_ = first == 0 && count == n;
    });
    one_leaf_ = one_leaf_ && leaves == 1 && !brute_force_;
    mesh = PlacedTriangles();
    build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Step 2 of the build: the BVH over the primitives' bounds (each a triangle, or a small shape
// where first_of_shape is given), handed over a block at a time, the mesh's box grown by each
// block's; without a BVH (brute force) the box alone.
void MeshAccel::build_tree(const PlacedTriangles& mesh, const std::vector<uint32_t>& first_of_shape,
                           const SearchSettings& settings) {
    const int threads = settings.threads;
    const size_t n = mesh.triangles.size();
    const size_t primitives = first_of_shape.empty() ? n : first_of_shape.size() - 1;
    std::mutex growing;
    auto primitive_bounds = [&](size_t first, size_t count, Bounds* out) {
        Bounds block;
        for (size_t k = 0; k < count; ++k) {
            const size_t p = first + k;
            out[k] = Bounds{};
            const size_t begin = first_of_shape.empty() ? p : first_of_shape[p];
            const size_t end = first_of_shape.empty() ? p + 1 : first_of_shape[p + 1];
            for (size_t triangle = begin; triangle < end; ++triangle)
                for (uint32_t v : mesh.triangles[triangle]) out[k].extend(mesh.positions[v]);
            block.extend(out[k]);
        }
        const std::lock_guard lock(growing);
        bounds_.extend(block);
    };
    if (brute_force_) {
        constexpr size_t kBlock = 256;
        Bounds out[kBlock];
        for (size_t first = 0; first < n; first += kBlock) primitive_bounds(first, std::min(kBlock, n - first), out);
    } else if (first_of_shape.empty()) {
        bvh_ = Bvh(n, primitive_bounds, settings.build, settings.leaf_size, threads, kTriangleLanes);
    } else {
        // The SAH and the leaf size count shapes: one of about `mean` triangles fills
        // kTriangleLanes / mean of a test's lanes.
        const uint32_t mean = uint32_t(std::max<size_t>(1, (n + primitives / 2) / primitives));
        const int lanes = int(std::bit_floor(std::max<uint32_t>(1, kTriangleLanes / mean)));
        const int leaf_size = std::max(1, settings.leaf_size / int(mean));
        bvh_ = Bvh(primitives, primitive_bounds, settings.build, leaf_size, threads, lanes);
        bvh_.expand(first_of_shape);
    }
}

// Step 3 of the build: the triangles' coordinates in leaf order (slot i holds triangle
// order[i], or i without a BVH), coordinate by coordinate; the positions are then freed.
void MeshAccel::store_triangles(PlacedTriangles& mesh, const std::vector<uint32_t>& order, int threads) {
    const size_t n = triangle_count_;
    auto triangle_in_slot = [&](size_t i) { return brute_force_ ? uint32_t(i) : order[i]; };
    const size_t stride = n + kTriangleLanes - 1;
    columns_.resize(9 * stride);  // uninitialised (LargeArray): each entry is written once
    Real* const columns = columns_.data();
    parallel_for(
        n,
        [&](size_t i) {
            const auto& v = mesh.triangles[triangle_in_slot(i)];
            for (int vertex = 0; vertex < 3; ++vertex)
                for (int axis = 0; axis < 3; ++axis)
                    columns[size_t(3 * vertex + axis) * stride + i] = mesh.positions[v[vertex]][axis];
        },
        threads);
    for (size_t column = 0; column < 9; ++column)  // the spare entries: never hit (no area)
        std::fill(columns + column * stride + n, columns + (column + 1) * stride, Real(0));
    release(mesh.positions);
    release(mesh.triangles);
}

// Step 3 of the build, continued: each slot's hit record and the vertex normals of the smooth
// triangles, in leaf order.
void MeshAccel::store_hit_records(const PlacedTriangles& mesh, const std::vector<uint32_t>& order, int threads) {
    const size_t n = triangle_count_;
    auto triangle_in_slot = [&](size_t i) { return brute_force_ ? uint32_t(i) : order[i]; };
    hit_records_.resize(n);
    size_t smooth = 0;
    if (mesh.normal_ids.empty()) {  // every triangle flat: no numbering of the smooth ones
        parallel_for(
            n,
            [&](size_t i) {
                const uint32_t triangle = triangle_in_slot(i);
                hit_records_[i] = {mesh.numbers[triangle], mesh.tags[triangle], kFlat};
            },
            threads);
    } else if (n >= kSerialBelow && std::none_of(mesh.normal_ids.begin(), mesh.normal_ids.end(),
                                                 [](const auto& ids) { return ids[0] == PlacedTriangles::kFlat; })) {
        // Every triangle of a large mesh smooth: each numbered by its slot, in parallel: serial
        // numbering was a tenth of the largest builds; below kSerialBelow the loop would not go
        // parallel and this path only costs time (docs/bench/code-figures.md).
        smooth = n;
        parallel_for(
            n,
            [&](size_t i) {
                const uint32_t triangle = triangle_in_slot(i);
                hit_records_[i] = {mesh.numbers[triangle], mesh.tags[triangle], uint32_t(i)};
            },
            threads);
    } else {
        for (size_t i = 0; i < n; ++i) {
            const uint32_t triangle = triangle_in_slot(i);
            const bool flat = mesh.normal_ids[triangle][0] == PlacedTriangles::kFlat;
            hit_records_[i] = {mesh.numbers[triangle], mesh.tags[triangle], flat ? kFlat : uint32_t(smooth++)};
        }
    }
    if (mesh.keep_uvs) {
        uvs_.resize(n);
        parallel_for(
            n, [&](size_t i) { uvs_[i] = mesh.uvs[triangle_in_slot(i)]; }, threads);
    }
    vertex_normals_.resize(smooth);
    parallel_for(
        n,
        [&](size_t i) {
            if (hit_records_[i].normals == kFlat) return;
            const auto& ids = mesh.normal_ids[triangle_in_slot(i)];
            vertex_normals_[hit_records_[i].normals] = {mesh.normals[ids[0]], mesh.normals[ids[1]],
                                                        mesh.normals[ids[2]]};
        },
        threads);
}

// The next Real above a finite positive x (std::nextafter without the library call).
static Real next_up(Real x) {
    using Bits = std::conditional_t<sizeof(Real) == 8, uint64_t, uint32_t>;
    return tracer::bit_cast<Real>(tracer::bit_cast<Bits>(x) + 1);
}

// The t at which the ray meets the triangle's plane, worked out in double: for a float build,
// whose watertight t is accurate relative to the triangle's extent along the ray rather than to
// t itself (hard case D1: 20 ulps off at t = 0.01 across a unit square). Differences and cross
// products of float coordinates are exact or nearly so in double, so t is good to about an ulp
// of float. nullopt for a ray in the plane.
[[maybe_unused]] static std::optional<double> plane_t(const Ray& ray, const Triangle& tri) {
    const glm::dvec3 v0(tri.v0), normal = glm::cross(glm::dvec3(tri.v1) - v0, glm::dvec3(tri.v2) - v0);
    const double along = glm::dot(glm::dvec3(ray.direction), normal);
    if (along == 0) return std::nullopt;
    return glm::dot(v0 - glm::dvec3(ray.origin), normal) / along;
}

// A lane tester's ray shear, for testing one triangle against several rays (RayLaneTester):
// the watertight rules only.
[[maybe_unused]] static const RayShear* shear_of(const TriangleLaneTester& tester) {
    return &tester.shear;
}
[[maybe_unused]] static const RayShear* shear_of(const MollerTrumboreLaneTester&) {
    return nullptr;
}

// One ray's search for its nearest triangle, leaf by leaf (intersect, intersect_packet).
// Ties: once a hit is found at t, a triangle at exactly t wins if it comes first in its file
// (lower part, then lower triangle number), whatever order the search meets them in
// (docs/robustness.md, hard case D2). So the test admits t up to one Real past r.max.
struct MeshAccel::NearestSearch {
    const MeshAccel& mesh;
    LaneTester tester;
    Real admit_max;
    uint32_t best = 0;
    TriangleHit best_hit;
    bool found = false;

    NearestSearch(const MeshAccel& m, const Ray& ray, Interval range)
        : mesh(m), tester(ray, m.columns()), admit_max(range.max) {}

    bool take(uint32_t i, const TriangleHit& hit, Interval& r) {
        if (hit.t == r.max) {
            if (!found) return false;  // the range is open: its end is no hit
            const HitRecord &a = mesh.hit_records_[i], &b = mesh.hit_records_[best];
            if (!(a.tag < b.tag || (a.tag == b.tag && a.triangle < b.triangle))) return false;
        }
        r.max = hit.t;
        admit_max = next_up(hit.t);
        best = i;
        best_hit = hit;
        found = true;
        // Read when the search ends, if no nearer hit.
        __builtin_prefetch(&mesh.hit_records_[i]);
        return true;
    }
    // Four triangles at a time; those that pass the vector steps are finished in order.
    bool test_leaf(uint32_t first, uint32_t count, Interval& r) {
        bool hit_here = false;
        for (uint32_t chunk = first; chunk < first + count; chunk += kTriangleLanes) {
            const int lanes = int(std::min<uint32_t>(kTriangleLanes, first + count - chunk));
            LaneTester::Candidate candidates[kTriangleLanes];
            for (unsigned m = tester.candidates(chunk, lanes, {r.min, admit_max}, candidates); m != 0; m &= m - 1) {
                const int lane = __builtin_ctz(m);
                TriangleHit hit;
                if (LaneTester::finish(candidates, lane, {r.min, admit_max}, hit))
                    hit_here |= take(chunk + uint32_t(lane), hit, r);
            }
        }
        return hit_here;
    }
    // The search's answer for `ray`, asked with range `asked`, now ending at `range`.
    bool finish(const Ray& ray, Interval asked, Interval& range, MeshHit& out) {
        if constexpr (std::is_same_v<Real, float>) {
            const auto t = found ? plane_t(ray, mesh.triangle(best)) : std::nullopt;
            if (t && Real(*t) > 0 && asked.contains(Real(*t))) best_hit.t = range.max = Real(*t);
        }
        if (found) out = {best, best_hit};
        return found;
    }
};

bool MeshAccel::intersect(const Ray& ray, Interval& range, MeshHit& out, TraversalCounts& counts) const {
    const Interval asked = range;
    NearestSearch nearest(*this, ray, range);
    search<false>(ray, range, counts,
                  [&](uint32_t first, uint32_t count, Interval& r) { return nearest.test_leaf(first, count, r); });
    return nearest.finish(ray, asked, range, out);
}

// A leaf's triangles one at a time against a group of up to kTriangleLanes rays at once
// (`tester`; `lanes`: those of its rays the leaf holds, ray i of the packet in lane i - base),
// each hit taken by its ray's own search(i), whose range then ends there and clip(i) follows.
template <typename Search, typename Clip>
[[gnu::always_inline]] static inline void leaf_sideways(RayLaneTester& tester, unsigned lanes, int base, uint32_t first,
                                                        uint32_t n, Interval* ranges, Search& search, Clip& clip) {
    RealLanes range_min, range_max;
    for (int lane = 0; lane < kTriangleLanes; ++lane) {
        const int i = base + (lanes >> lane & 1 ? lane : __builtin_ctz(lanes));
        range_min[lane] = ranges[i].min, range_max[lane] = search(i).admit_max;
    }
    for (uint32_t triangle = first; triangle < first + n; ++triangle) {
        ShearedTriangle sheared[kTriangleLanes];
        unsigned m = tester.candidates(triangle, range_min, range_max, sheared) & lanes;
        for (; m != 0; m &= m - 1) {
            const int lane = __builtin_ctz(m), i = base + lane;
            TriangleHit hit;
            if (!TriangleLaneTester::finish(sheared, lane, {ranges[i].min, search(i).admit_max}, hit) ||
                !search(i).take(triangle, hit, ranges[i]))
                continue;
            range_max[lane] = search(i).admit_max;
            clip(i);
        }
    }
}

unsigned MeshAccel::intersect_packet(const Ray* const* rays, int count, Interval* ranges, MeshHit* out,
                                     TraversalCounts& counts) const {
    // Step 1: the rays' box tests side by side, if they agree in form (else one by one).
    unsigned found = 0;
    // Made in place: a copy out of the constructor's just-written temporary stalls (store-to-load
    // forwarding fails on the wide loads), a third of this function's time on the bunny room.
    alignas(TraversalRay) unsigned char fast_storage[kPacket][sizeof(TraversalRay)];
    TraversalRay* fast = std::launder(reinterpret_cast<TraversalRay*>(fast_storage));
    for (int i = 0; i < count; ++i) new (&fast[i]) TraversalRay(*rays[i], ranges[i]);
    TraversalPacket packet;
    if (brute_force_ || bvh_.wide() == nullptr || !TraversalPacket::make(fast, count, packet)) {
        for (int i = 0; i < count; ++i) found |= unsigned(intersect(*rays[i], ranges[i], out[i], counts)) << i;
        return found;
    }
    // Step 2: each ray's own leaf search, through the nodes together. Set up when the first
    // leaf is reached (most rays that miss the mesh never reach one), for every ray at once.
    alignas(NearestSearch) unsigned char storage[kPacket][sizeof(NearestSearch)];
    auto search = [&](int i) -> NearestSearch& { return *std::launder(reinterpret_cast<NearestSearch*>(storage[i])); };
    bool started = false;
    Interval asked[kPacket];
    std::copy(ranges, ranges + count, asked);
    // Rays whose shears share their axes (all, most often) test a leaf's triangles one at a time
    // against four rays at once (RayLaneTester): groups of rays 0-3 and 4-7.
    constexpr int kGroups = kPacket / kTriangleLanes;
    alignas(RayLaneTester) unsigned char group_storage[kGroups][sizeof(RayLaneTester)];
    auto group = [&](int g) -> RayLaneTester& {
        return *std::launder(reinterpret_cast<RayLaneTester*>(group_storage[g]));
    };
    bool sideways = false;
    auto start = [&] {
        for (int i = 0; i < count; ++i) new (storage[i]) NearestSearch(*this, *rays[i], ranges[i]);
        started = true;
        if constexpr (kRobust) {
            const RayShear* shears[kPacket];
            sideways = true;
            for (int i = 0; i < count; ++i) {
                shears[i] = shear_of(search(i).tester);
                sideways = sideways && shears[i]->kx == shears[0]->kx && shears[i]->ky == shears[0]->ky;
            }
            for (int g = 0; sideways && g * kTriangleLanes < count; ++g)
                new (group_storage[g]) RayLaneTester(shears + g * kTriangleLanes,
                                                     std::min(kTriangleLanes, count - g * kTriangleLanes), columns());
        }
    };
    // Ray i's box tests end at its nearest hit so far (TraversalRay::clip, lane i).
    auto clip = [&](int i) { packet.t_max[i] = std::min(packet.t_max[i], round_up(ranges[i].max)); };
    auto leaf = [&](unsigned in_leaf, uint32_t first, uint32_t n) {
        counts.primitive_tests += n * uint32_t(std::popcount(in_leaf));
        if (!started) start();
        if constexpr (kRobust) {
            if (sideways) {
                for (int g = 0; g < kGroups; ++g) {
                    const unsigned lanes = in_leaf >> (g * kTriangleLanes) & ((1u << kTriangleLanes) - 1);
                    if (lanes != 0) leaf_sideways(group(g), lanes, g * kTriangleLanes, first, n, ranges, search, clip);
                }
                return;
            }
        }
        for (; in_leaf != 0; in_leaf &= in_leaf - 1) {
            const int i = __builtin_ctz(in_leaf);
            if (search(i).test_leaf(first, n, ranges[i])) clip(i);
        }
    };
    bvh_.wide()->closest_in_packet(packet, counts, leaf);
    for (int i = 0; started && i < count; ++i)
        found |= unsigned(search(i).finish(*rays[i], asked[i], ranges[i], out[i])) << i;
    return found;
}

template <bool kAny, typename TestLeaf>
bool MeshAccel::search(const Ray& ray, Interval& range, TraversalCounts& counts, TestLeaf test_leaf) const {
    if (brute_force_ || one_leaf_) {
        counts.primitive_tests += triangle_count_;
        return test_leaf(0, uint32_t(triangle_count_), range);
    }
    if constexpr (kAny)
        return bvh_.any(ray, range, counts, LeafTest{test_leaf});
    else
        return bvh_.closest(ray, range, counts, LeafTest{test_leaf});
}

void MeshAccel::all_hits(const Ray& ray, Interval range, std::vector<MeshHit>& out, TraversalCounts& counts) const {
    const LaneTester tester(ray, columns());
    search<false>(ray, range, counts, [&](uint32_t first, uint32_t count, Interval& r) {
        for (uint32_t chunk = first; chunk < first + count; chunk += kTriangleLanes) {
            const int lanes = int(std::min<uint32_t>(kTriangleLanes, first + count - chunk));
            LaneTester::Candidate candidates[kTriangleLanes];
            for (unsigned m = tester.candidates(chunk, lanes, r, candidates); m != 0; m &= m - 1) {
                const int lane = __builtin_ctz(m);
                TriangleHit hit;
                if (LaneTester::finish(candidates, lane, r, hit)) out.push_back({chunk + uint32_t(lane), hit});
            }
        }
        return false;  // the range stays whole: every hit is wanted
    });
}

[[gnu::always_inline]] inline bool MeshAccel::run_blocks(const LaneTester& tester, TriangleRun run, Interval range) {
    LaneTester::Candidate candidates[kTriangleLanes];
    for (unsigned m = tester.candidates(run.first, int(run.count), range, candidates); m != 0; m &= m - 1) {
        TriangleHit hit;
        if (LaneTester::finish(candidates, __builtin_ctz(m), range, hit)) return true;
    }
    return false;
}

bool MeshAccel::occluded(const Ray& ray, Interval range, TraversalCounts& counts, TriangleRun& blocker) const {
    // Each leaf in runs of as many triangles as one test takes; the run that blocks is kept.
    const LaneTester tester(ray, columns());
    return search<true>(ray, range, counts, [&](uint32_t first, uint32_t count, Interval& r) {
        for (uint32_t start = first; start < first + count; start += kTriangleLanes) {
            const TriangleRun run{start, std::min(uint32_t(kTriangleLanes), first + count - start)};
            if (run_blocks(tester, run, r)) {
                blocker = run;
                return true;
            }
        }
        return false;
    });
}

bool MeshAccel::blocks(TriangleRun run, const Ray& ray, Interval range) const {
    return run_blocks(LaneTester(ray, columns()), run, range);
}

bool MeshAccel::leaves_block(const TriangleRun* leaves, int count, const Ray& ray, Interval range,
                             TraversalCounts& counts, TriangleRun& blocker) const {
    const LaneTester tester(ray, columns());
    for (int k = 0; k < count; ++k) {
        const uint32_t first = leaves[k].first, end = leaves[k].first + leaves[k].count;
        counts.primitive_tests += leaves[k].count;
        for (uint32_t start = first; start < end; start += kTriangleLanes) {
            const TriangleRun run{start, std::min(uint32_t(kTriangleLanes), end - start)};
            if (run_blocks(tester, run, range)) {
                blocker = run;
                return true;
            }
        }
    }
    return false;
}

Vec3 MeshAccel::surface_point(uint32_t slot, Real u, Real v, Vec3& error) const {
    const Triangle t = triangle(slot);
    const Real w = 1 - u - v;
    const Vec3 a = w * t.v0, b = u * t.v1, c = v * t.v2;
    // The weights sum to 1 only up to the rounding of w: that moves the point by up to
    // gamma(2) |v0| off the affine combination.
    error = gamma(7) * (abs_each(a) + abs_each(b) + abs_each(c)) + gamma(3) * abs_each(t.v0);
    return a + b + c;
}

glm::dvec2 MeshAccel::surface_uv(uint32_t slot, Real u, Real v) const {
    if (uvs_.empty()) return glm::dvec2(0.0);
    const std::array<glm::vec2, 3>& c = uvs_[slot];
    const double a = double(u), b = double(v);
    return (1 - a - b) * glm::dvec2(c[0]) + a * glm::dvec2(c[1]) + b * glm::dvec2(c[2]);
}

Vec3 MeshAccel::geometric_normal(uint32_t slot) const {
    const Triangle t = triangle(slot);
    return normalize_or_zero(glm::cross(t.v1 - t.v0, t.v2 - t.v0));
}

std::array<Vec3, 3> MeshAccel::vertex_normals(uint32_t slot) const {
    const uint32_t index = hit_records_[slot].normals;
    if (index != kFlat) return vertex_normals_[index];
    // As a flat part's vertex normals were once stored: the same Real corners, the same formula.
    const Vec3 face = geometric_normal(slot);
    return {face, face, face};
}

Vec3 MeshAccel::shading_normal(uint32_t slot, Real u, Real v) const {
    const std::array<Vec3, 3> n = vertex_normals(slot);
    const Vec3 shading = normalize_or_zero((1 - u - v) * n[0] + u * n[1] + v * n[2]);
    return shading != Vec3(0) ? shading : geometric_normal(slot);
}

Vec3 MeshAccel::shading_normal(uint32_t slot, Real u, Real v, const Mat3& normal_map) const {
    const std::array<Vec3, 3> n = vertex_normals(slot);
    const Vec3 shading =
        normalize_or_zero((1 - u - v) * normalize_or_zero(normal_map * n[0]) +
                          u * normalize_or_zero(normal_map * n[1]) + v * normalize_or_zero(normal_map * n[2]));
    return shading != Vec3(0) ? shading : normalize_or_zero(normal_map * geometric_normal(slot));
}

size_t MeshAccel::memory_bytes() const {
    return bvh_.memory_bytes() + columns_.capacity() * sizeof(Real) + hit_records_.capacity() * sizeof(HitRecord) +
           vertex_normals_.capacity() * sizeof(vertex_normals_[0]) + uvs_.capacity() * sizeof(uvs_[0]);
}

}  // namespace tracer
