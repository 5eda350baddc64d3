#include "accel/world.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "accel/geometry.h"
#include "accel/shape_bounds.h"
#include "scene/flat_shapes.h"

namespace tracer {
namespace {

// The top level's leaves hold at most this many objects (measured: docs/bench/many-objects.md).
constexpr int kTopLeafSize = 1;
// From this many bounded objects on, the top level gathers subtrees of up to kGatheredSpheres
// spheres into one leaf (LeafGathering): a node per few spheres leaves most of its eight lanes
// empty. That saves memory from this size on, for the same render time; below it, leaves of
// one render faster, with fewer sphere tests (docs/bench/code-figures.md).
constexpr size_t kGatherFrom = size_t(1) << 19;
constexpr uint32_t kGatheredSpheres = 6;
// How far below a shared mesh's BVH root its instances' world boxes are taken from: the placed
// corners of the boxes there (up to 64 in a wide tree) bound a rotated mesh far more tightly
// than the placed corners of its whole box.
constexpr int kInstanceBoxLevels = 2;

SearchSettings search_settings(const RenderSettings& render, int threads) {
    SearchSettings settings;
    settings.brute_force = render.accel == Accelerator::None;
    settings.build = render.accel == Accelerator::Box      ? BvhBuild::Box
                     : render.accel == Accelerator::Median ? BvhBuild::Median
                                                           : BvhBuild::Sah;
    settings.leaf_size = render.leaf_size;
    settings.threads = threads;
    return settings;
}

// Half the diagonal of `box`: a sphere around its center holding it (infinite where the
// diagonal overflows).
Real half_diagonal(const Bounds& box) {
    const Real radius = glm::length(box.upper - box.lower) * Real(0.5);
    return std::isfinite(radius) ? radius : kInfinity;
}

double surface_area(const Bounds& box) {
    const glm::dvec3 size = glm::dvec3(box.upper) - glm::dvec3(box.lower);
    return 2 * (size.x * size.y + size.y * size.z + size.z * size.x);
}

// A long cone leaning across the axes fills little of its box, which then overlaps its
// neighbours' and is entered by rays that pass it by. Cut along its axis into pieces, each with
// the box of its own stretch (early split clipping, Ernst and Greiner 2007, for one shape), the
// boxes hug it; a ray entering any piece tests the whole cone. One more piece while it cuts the
// boxes' total area by kConePieceGain; other gains measured alike (docs/bench/code-figures.md).
constexpr int kMostConePieces = 16;
constexpr double kConePieceGain = 0.9;

// The boxes of `cone` (its unit `axis` given) cut into at most `most` pieces.
std::vector<Bounds> cone_piece_boxes(const Cone& cone, const glm::dvec3& axis, int most) {
    auto pieces = [&](int count) {
        std::vector<Bounds> boxes(count);
        double area = 0;
        for (int i = 0; i < count; ++i) {
            const double from = double(i) / count, to = double(i + 1) / count;
            boxes[i] =
                disc_box(glm::mix(cone.base, cone.top, from), axis, std::lerp(cone.base_radius, cone.top_radius, from));
            boxes[i].extend(
                disc_box(glm::mix(cone.base, cone.top, to), axis, std::lerp(cone.base_radius, cone.top_radius, to)));
            area += surface_area(boxes[i]);
        }
        return std::pair{boxes, area};
    };
    auto best = pieces(1);
    for (int count = 2; count <= most; ++count) {
        auto more = pieces(count);
        if (!(more.second < kConePieceGain * best.second)) break;
        best = std::move(more);
    }
    return best.first;
}

}  // namespace

World::World(const SceneDescription& scene, const SceneMeshes& meshes, int threads, bool flatten_shared)
    : World(scene, meshes, threads, flatten_shared, nullptr, nullptr) {}

World::World(SceneDescription& scene, const SceneMeshes& meshes, int threads, ReleaseFlatShapes)
    : World(scene, meshes, threads, false, &scene, nullptr) {}

World::World(SceneDescription& scene, const SceneMeshes& meshes, int threads, ReleaseFlatShapes, MeshBuildCache& reuse)
    : World(scene, meshes, threads, false, &scene, &reuse) {}

World::World(const SceneDescription& scene, const SceneMeshes& meshes, int threads, bool flatten_shared,
             SceneDescription* releasable, MeshBuildCache* reuse)
    : solids_(scene, meshes, search_settings(scene.render, threads)),
      materials_(scene.materials),
      lights_(scene.lights),
      patterns_(scene.patterns),
      images_(scene.images) {
    static std::atomic<uint64_t> worlds{0};
    serial_ = ++worlds;
    for (const Material& material : materials_) refracts_ = refracts_ || material.kt != dvec3(0.0);
    SearchSettings settings = search_settings(scene.render, threads);
    settings.keep_uvs = uses_surface_coordinates(scene.patterns);
    if (settings.keep_uvs)
        for (const Material& material : materials_)
            uv_materials_.push_back(tracer::maps_by_uv(patterns_, material.ka_pattern) ||
                                    tracer::maps_by_uv(patterns_, material.kd_pattern));
    if (!patterns_.empty())
        for (const Material& material : materials_)
            ka_scales_kd_.push_back(same_but_multiply(patterns_, material.ka_pattern, material.kd_pattern));
    // Step 1: spheres and planes (room for them at once: a million spheres would otherwise
    // leave up to a million records' room unused).
    objects_.reserve(scene.spheres.size() + scene.planes.size());
    bounded_.reserve(scene.spheres.size());
    boxes_.reserve(scene.spheres.size());
    for (const Sphere& s : scene.spheres) {
        const uint32_t entry = uint32_t(bounded_.size()), object = uint32_t(objects_.size());
        objects_.push_back({ObjectKind::Sphere, entry, s.material});
        bounded_.push_back({Vec3(s.center), Real(s.radius), object, 0, ObjectKind::Sphere});
        boxes_.push_back({Vec3(s.center) - Real(s.radius), Vec3(s.center) + Real(s.radius)});
    }
    sphere_count_ = uint32_t(bounded_.size());
    for (const Plane& p : scene.planes) {
        objects_.push_back({ObjectKind::Plane, uint32_t(planes_.size()), p.material});
        planes_.push_back({Vec3(p.point), Vec3(p.normal), uint32_t(objects_.size() - 1)});
    }
    // Step 2: the meshes, each file built once, and an instance per mesh block; then the cones
    // and discs (numbered after every older kind, so that older scenes keep their order).
    add_meshes(scene, meshes, settings, flatten_shared, releasable, reuse);
    add_round_shapes(scene, settings);
    add_solids();
    // Step 3: the top level over every bounded object.
    build_top_level(settings);
}

void World::add_bounded(const Bounds& box, uint32_t object, uint32_t index, ObjectKind kind) {
    bounded_.push_back({box.center(), half_diagonal(box), object, index, kind});
    boxes_.push_back(box);
}

void World::add_round_shapes(const SceneDescription& scene, const SearchSettings& settings) {
    // Pieces only help a BVH: tested one by one, a cone is tested once, whole.
    const bool bvh =
        !settings.brute_force && bounded_.size() + scene.cones.size() + scene.discs.size() > kLinearObjects;
    for (const Cone& c : scene.cones) {
        const glm::dvec3 axis = (c.top - c.base) / glm::length(c.top - c.base);
        const uint32_t index = uint32_t(cones_.size()), object = uint32_t(objects_.size());
        objects_.push_back({ObjectKind::Cone, index, c.material});
        cones_.push_back(make_cone_shape(c.base, c.top, c.base_radius, c.top_radius, c.caps));
        if (settings.keep_uvs) cone_ends_.push_back({c.base, c.top, c.base_radius, c.top_radius});
        const std::vector<Bounds> pieces = cone_piece_boxes(c, axis, bvh ? kMostConePieces : 1);
        for (const Bounds& box : pieces) add_bounded(box, object, index, ObjectKind::Cone);
        extra_entries_ += pieces.size() - 1;
    }
    for (const Disc& d : scene.discs) {
        const uint32_t index = uint32_t(discs_.size()), object = uint32_t(objects_.size());
        objects_.push_back({ObjectKind::Disc, index, d.material});
        discs_.push_back({Vec3(d.center), Vec3(d.normal), Real(d.radius)});
        add_bounded(disc_box(d.center, d.normal, d.radius), object, index, ObjectKind::Disc);
    }
}

void World::add_solids() {
    for (uint32_t index = 0; index < solids_.size(); ++index) {
        const uint32_t object = uint32_t(objects_.size());
        objects_.push_back({ObjectKind::Solid, index, 0});  // the material is each face's
        if (solids_.bounded(index))
            add_bounded(solids_.bounds(index), object, index, ObjectKind::Solid);
        else
            unbounded_solids_.push_back({index, object});
    }
}

void World::add_meshes(const SceneDescription& scene, const SceneMeshes& meshes, const SearchSettings& settings,
                       bool flatten_shared, SceneDescription* releasable, MeshBuildCache* reuse) {
    std::vector<int> blocks_of_file(meshes.files.size(), 0);
    for (uint32_t file : meshes.file_of_block) ++blocks_of_file[file];
    std::map<std::pair<uint32_t, bool>, uint32_t> shared_mesh;  // (file, flat) -> index into meshes_
    std::vector<MeshPart> merged;                               // the blocks built placed, in one mesh
    std::vector<uint32_t> merged_instances;
    for (size_t block = 0; block < scene.meshes.size() && block < meshes.file_of_block.size(); ++block) {
        const Mesh& mesh = scene.meshes[block];
        const uint32_t file = meshes.file_of_block[block];
        const Placement placement(mesh);
        const uint32_t index = uint32_t(instances_.size()), object = uint32_t(objects_.size());
        objects_.push_back({ObjectKind::MeshInstance, index, mesh.material});
        MeshInstance instance;
        if ((blocks_of_file[file] == 1 || flatten_shared) && !reuse) {
            // Placed in world coordinates, with every other such block, in one mesh.
            merged.push_back({meshes.files[file].get(), placement, object, mesh.flat});
            merged_instances.push_back(index);
        } else {
            // Shared (or a frame of an animation): built once in the file's coordinates; rays are
            // carried there.
            auto [known, is_new] = shared_mesh.try_emplace({file, mesh.flat}, uint32_t(meshes_.size()));
            if (is_new && reuse)
                meshes_.push_back(reuse->get(meshes.files[file], mesh.flat, settings));
            else if (is_new)
                meshes_.emplace_back(*meshes.files[file], Placement(), settings, mesh.flat);
            instance.mesh = known->second;
            instance.placed = false;
            instance.to_world = Mat3(placement.linear);
            instance.to_object = Mat3(glm::inverse(placement.linear));
            instance.translate = Vec3(placement.translate);
            const MeshAccel& shared = meshes_[instance.mesh];
            const std::vector<Bounds> cover =
                shared.brute_force() ? std::vector<Bounds>{shared.bounds()} : shared.bvh().cover(kInstanceBoxLevels);
            Bounds box;
            for (const Bounds& part : cover) box.extend(placed_box(part, placement));
            add_bounded(box, object, index);
        }
        instances_.push_back(instance);
    }
    // The flat shapes (triangle, quad, box): placed and merged too, straight into the merged
    // triangles, sharing one instance; the work and memory per shape are a few triangles'.
    const size_t flat_shapes = scene.triangles.size() + scene.quads.size() + scene.boxes.size();
    if (merged.empty() && flat_shapes == 0) return;
    PlacedTriangles placed =
        place(merged, settings.threads, 3 * scene.triangles.size() + 4 * scene.quads.size() + 8 * scene.boxes.size(),
              scene.triangles.size() + 2 * scene.quads.size() + 12 * scene.boxes.size(), settings.keep_uvs);
    if (flat_shapes > 0) {
        merged_instances.push_back(uint32_t(instances_.size()));
        instances_.emplace_back();
    }
    auto add_flat = [&](const Placed& shape, const TriangleMesh& mesh) {
        const uint32_t object = uint32_t(objects_.size());
        objects_.push_back({ObjectKind::MeshInstance, merged_instances.back(), shape.material});
        append_part(placed, {&mesh, Placement(shape), object, true}, 1);
    };
    for (const FlatTriangle& shape : scene.triangles) add_flat(shape, triangle_mesh(shape));
    for (const Quad& shape : scene.quads) add_flat(shape, triangle_mesh(shape));
    for (const Box& shape : scene.boxes) add_flat(shape, triangle_mesh(shape));
    if (releasable) {  // placed: their descriptions are not needed again
        // Move-assigned, not `= {}`: that clears a vector but keeps its memory.
        releasable->triangles = std::vector<FlatTriangle>();
        releasable->quads = std::vector<Quad>();
        releasable->boxes = std::vector<Box>();
    }
    for (uint32_t index : merged_instances) instances_[index].mesh = uint32_t(meshes_.size());
    merged_mesh_ = uint32_t(meshes_.size());
    // One shape alone needs no look-up of its triangles' tag (the hit record's cache line).
    const bool one_shape = merged.size() + flat_shapes == 1;
    const uint32_t only_tag = placed.tags.empty() ? 0 : placed.tags.front();
    meshes_.emplace_back(std::move(placed), settings);
    add_bounded(meshes_.back().bounds(), one_shape ? only_tag : kObjectOfTriangle, merged_instances.front());
}

void World::build_top_level(const SearchSettings& settings) {
    const auto start = std::chrono::steady_clock::now();
    Bounds all;
    for (const Bounds& box : boxes_) all.extend(box);
    if (!bounded_.empty()) {
        const Real radius = half_diagonal(all);
        sphere_center_ = all.center();
        sphere_radius2_ = radius * radius;
    }
    linear_ = settings.brute_force || bounded_.size() - extra_entries_ <= kLinearObjects;
    packet_search_possible_ =
        linear_ && std::any_of(bounded_.begin(), bounded_.end(), [&](const Bounded& b) {
            return b.kind == ObjectKind::MeshInstance && !meshes_[instances_[b.index].mesh].one_leaf();
        });
    for (const MeshInstance& instance : instances_)
        largest_mesh_triangles_ = std::max(largest_mesh_triangles_, meshes_[instance.mesh].triangle_count());
    if (!linear_) {
        LeafGathering gathering;
        if (bounded_.size() >= kGatherFrom)
            gathering = {kGatheredSpheres, [&](uint32_t id) { return bounded_[id].kind == ObjectKind::Sphere; }};
        top_ = Bvh(std::move(boxes_), BvhBuild::Sah, kTopLeafSize, settings.threads, 1, gathering);
        // The entries in leaf order: the BVH's leaves then count them directly, and its order
        // is needed no more.
        std::vector<Bounded> in_leaf_order;
        in_leaf_order.reserve(bounded_.size());
        for (uint32_t i : top_.take_order()) in_leaf_order.push_back(bounded_[i]);
        bounded_ = std::move(in_leaf_order);
        for (uint32_t entry = 0; entry < bounded_.size(); ++entry)  // a sphere's object follows it
            if (bounded_[entry].kind == ObjectKind::Sphere) objects_[bounded_[entry].object].index = entry;
    }
    if (linear_)
        for (const Bounds& box : boxes_) linear_boxes_.push_back(padded_for_rays(box));
    boxes_ = decltype(boxes_)();  // only the build needs them (`= {}` would keep the memory)
    top_build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool World::may_hit(const Ray& ray) const {
    if (!planes_.empty() || !unbounded_solids_.empty()) return true;
    if (!linear_) return line_may_meet_sphere(ray, sphere_center_, sphere_radius2_);
    for (size_t entry = 0; entry < bounded_.size(); ++entry)
        if (may_meet_entry(entry, ray, Interval{})) return true;
    return false;
}

size_t World::top_level_memory_bytes() const {
    return top_.memory_bytes() + bounded_.capacity() * sizeof(Bounded) + objects_.capacity() * sizeof(Object) +
           instances_.capacity() * sizeof(MeshInstance) + planes_.capacity() * sizeof(PlaneShape) +
           cones_.capacity() * sizeof(ConeShape) + discs_.capacity() * sizeof(DiscShape);
}

// Fewer rays than this that may meet a mesh search it one by one (nearest_hits).
constexpr int kFewestInPacket = 2;

bool World::packet_shares_a_mesh(const Ray* const* rays, int count) const {
    if (!packet_search_possible_) return false;
    for (size_t e = sphere_count_; e < bounded_.size(); ++e) {
        const Bounded& b = bounded_[e];
        if (b.kind != ObjectKind::MeshInstance) continue;
        int n = 0;
        for (int i = 0; i < count; ++i) n += line_may_meet_sphere(*rays[i], b.center, b.radius * b.radius);
        if (n >= kFewestInPacket) return true;
    }
    return false;
}

void World::nearest_hits(const Ray* const* rays, int count, Interval range, std::optional<Hit>* out,
                         SearchCounts& counts) const {
    if (!linear_ || count == 1) {
        for (int i = 0; i < count; ++i) out[i] = nearest_hit(*rays[i], range, counts);
        return;
    }
    // Step 1: spheres and planes, ray by ray (as nearest_one_by_one, in the same order).
    Interval ranges[kPacket];
    Hit hits[kPacket];
    bool found[kPacket] = {};
    for (int i = 0; i < count; ++i) {
        Interval r = range;  // kept in registers while the ray's spheres are tested
        Hit hit;
        found[i] = nearest_sphere_or_plane(*rays[i], r, hit, kNoObject);
        ranges[i] = r;
        hits[i] = hit;
    }
    // Step 2: the other objects in order; each mesh for the rays that may meet it, together.
    for (size_t e = sphere_count_; e < bounded_.size(); ++e) {
        const Bounded& b = bounded_[e];
        int members[kPacket];
        int n = 0;
        for (int i = 0; i < count; ++i)
            if (may_meet_entry(e, *rays[i], ranges[i])) members[n++] = i;
        if (b.kind != ObjectKind::MeshInstance || n < kFewestInPacket) {
            for (int k = 0; k < n; ++k)
                found[members[k]] = hit_bounded(b, *rays[members[k]], ranges[members[k]], hits[members[k]], counts) ||
                                    found[members[k]];
            continue;
        }
        const MeshInstance& instance = instances_[b.index];
        const MeshAccel& mesh = meshes_[instance.mesh];
        Ray placed[kPacket];  // the rays in the mesh's coordinates, if it is not built placed
        const Ray* local[kPacket];
        Interval local_ranges[kPacket];
        MeshHit mesh_hits[kPacket];
        for (int k = 0; k < n; ++k) {
            if (instance.placed) {
                local[k] = rays[members[k]];
            } else {
                placed[k] = instance.to_mesh(*rays[members[k]]);
                local[k] = &placed[k];
            }
            local_ranges[k] = ranges[members[k]];
        }
        const unsigned met = n == 0 ? 0 : mesh.intersect_packet(local, n, local_ranges, mesh_hits, counts.triangles);
        for (unsigned m = met; m != 0; m &= m - 1) {
            const int k = __builtin_ctz(m), i = members[k];
            ranges[i] = local_ranges[k];
            hits[i] = {b.object != kObjectOfTriangle ? b.object : mesh.tag_of(mesh_hits[k].slot), mesh_hits[k].slot,
                       ranges[i].max, mesh_hits[k].hit.u, mesh_hits[k].hit.v};
            found[i] = true;
        }
    }
    counts.objects.primitive_tests += bounded_.size() * size_t(count);
    for (int i = 0; i < count; ++i) out[i] = found[i] ? std::optional<Hit>(hits[i]) : std::nullopt;
}

}  // namespace tracer
