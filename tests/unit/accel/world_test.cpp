// The two-level search (a BVH over the objects, each mesh's BVH below it, instances placed by
// transforming rays) against brute force over every primitive of the placed scene.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include <glm/geometric.hpp>

#include "../../common/nearest_surface.h"
#include "../../common/sweep.h"
#include "accel/geometry.h"
#include "accel/triangle.h"
#include "accel/world.h"
#include "io/obj_mesh.h"
#include "scene/placement.h"

namespace tracer {
namespace {

const std::filesystem::path kMeshes = std::filesystem::path(TRACER_SOURCE_DIR) / "scenes" / "meshes";

TriangleMesh read(const std::string& name) {
    Mesh block;
    block.path = (kMeshes / name).string();
    Diagnostics diagnostics;
    auto mesh = load_mesh(block, diagnostics);
    EXPECT_TRUE(mesh) << name;
    return mesh ? *mesh : TriangleMesh{};
}

// A mixed scene: `spheres` random spheres, a floor plane, the bunny placed five times (rotated
// about tilted axes, scaled non-uniformly), the tetrahedron three times and a one-off
// triangle soup (which the world builds placed rather than instanced).
struct MixedScene {
    SceneDescription scene;
    SceneMeshes meshes;
};

MixedScene mixed_scene(int spheres, uint32_t seed, Accelerator accel = Accelerator::Sah) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(0, 1);
    MixedScene out;
    SceneDescription& scene = out.scene;
    scene.render.accel = accel;
    scene.materials.resize(4);
    for (int i = 0; i < spheres; ++i)
        scene.spheres.push_back({{8 * unit(random) - 4, 8 * unit(random) - 4, 8 * unit(random) - 4},
                                 0.02 + 0.3 * unit(random) * unit(random),
                                 i % 4});
    scene.planes.push_back({{0, -6, 0}, {0, 1, 0}, 1});

    TriangleMesh soup;
    for (int i = 0; i < 200; ++i) {
        const glm::dvec3 center(2 * unit(random) - 1, 2 * unit(random) - 1, 2 * unit(random) - 1);
        const uint32_t first = uint32_t(soup.positions.size());
        for (int k = 0; k < 3; ++k)
            soup.positions.push_back(center +
                                     0.3 * glm::dvec3(unit(random) - 0.5, unit(random) - 0.5, unit(random) - 0.5));
        soup.triangles.push_back({first, first + 1, first + 2});
    }
    out.meshes.files = {share_mesh(read("bunny.obj")), share_mesh(read("tetrahedron.obj")), share_mesh(soup)};
    auto place = [&](uint32_t file, dvec3 scale, double angle) {
        Mesh block;
        block.scale = scale;
        block.rotate_axis = glm::normalize(dvec3(unit(random) - 0.5, 1, unit(random) - 0.5));
        block.rotate_degrees = angle;
        block.translate = {8 * unit(random) - 4, 8 * unit(random) - 4, 8 * unit(random) - 4};
        block.material = int(file) + 1;
        scene.meshes.push_back(block);
        out.meshes.file_of_block.push_back(file);
    };
    for (int i = 0; i < 5; ++i)
        place(0, dvec3(0.1 + 0.1 * unit(random), 0.1, 0.15 + 0.1 * unit(random)), 360 * unit(random));
    for (int i = 0; i < 3; ++i) place(1, dvec3(0.5 + unit(random), 0.7, 1.2), 360 * unit(random));
    place(2, dvec3(1.5, 1, 0.8), 30);
    return out;
}

// The nearest hit found by testing every sphere, plane and placed triangle in world
// coordinates, independently of World: its object (numbered as World numbers them: spheres,
// planes, mesh blocks) and t.
struct BruteHit {
    bool found = false;
    uint32_t object = 0;
    Real t = kInfinity;
};

class BruteForce {
public:
    explicit BruteForce(const MixedScene& mixed) : scene_(mixed.scene) {
        for (size_t block = 0; block < scene_.meshes.size(); ++block) {
            const Placement placement(scene_.meshes[block]);
            const TriangleMesh& file = *mixed.meshes.files[mixed.meshes.file_of_block[block]];
            std::vector<Triangle> placed;
            for (const auto& t : file.triangles)
                placed.push_back({placement.point(file.positions[t[0]]), placement.point(file.positions[t[1]]),
                                  placement.point(file.positions[t[2]])});
            triangles_.push_back(std::move(placed));
        }
    }

    BruteHit nearest(const Ray& ray, Interval range) const {
        BruteHit best;
        uint32_t object = 0;
        auto take = [&](Real t) {
            best = {true, object, t};
            range.max = t;
        };
        for (const Sphere& s : scene_.spheres) {
            if (auto t = intersect_sphere(ray, s.center, s.radius, range)) take(*t);
            ++object;
        }
        for (const Plane& p : scene_.planes) {
            if (auto t = intersect_plane(ray, p.point, p.normal, range)) take(*t);
            ++object;
        }
        const TriangleTester tester(ray);
        for (const auto& mesh : triangles_) {
            for (const Triangle& triangle : mesh) {
                TriangleHit hit;
                if (tester(triangle, range, hit)) take(hit.t);
            }
            ++object;
        }
        return best;
    }

private:
    const SceneDescription& scene_;
    std::vector<std::vector<Triangle>> triangles_;
};

// Rays from a sphere around the scene towards random points of its box, and from random
// points inside it in random directions (as secondary rays start).
std::vector<Ray> random_rays(int full_count, uint32_t seed) {
    const int count = int(sweep(size_t(full_count)));  // fewer under the sanitizers
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(0, 1);
    std::normal_distribution<double> gauss;
    std::vector<Ray> rays;
    for (int i = 0; i < count; ++i) {
        const Vec3 inside(10 * unit(random) - 5, 10 * unit(random) - 5, 10 * unit(random) - 5);
        const Vec3 direction = glm::normalize(Vec3(gauss(random), gauss(random), gauss(random)));
        if (i % 2) {
            rays.push_back({inside, direction});
        } else {
            const Vec3 origin = Real(20) * direction;
            rays.push_back({origin, glm::normalize(inside - origin)});
        }
    }
    return rays;
}

// The same arithmetic through both levels and with every primitive tested (accel none): the
// same objects at the same t (to an ulp or two), the same normals and materials.
TEST(World, TwoLevelSearchFindsExactlyWhatTestingEveryPrimitiveFinds) {
    const MixedScene mixed = mixed_scene(400, 1), brute_mixed = mixed_scene(400, 1, Accelerator::None);
    const World world(mixed.scene, mixed.meshes), brute(brute_mixed.scene, brute_mixed.meshes);
    ASSERT_FALSE(world.top_level_linear());
    ASSERT_TRUE(brute.top_level_linear());
    ASSERT_EQ(world.meshes().size(), 3u);  // bunny and tetrahedron shared, the soup placed
    int hits = 0, instance_hits = 0;
    std::mt19937 random(3);
    std::uniform_real_distribution<double> fraction(0, 2);
    for (const Ray& ray : random_rays(100000, 2)) {
        SearchCounts counts;
        const auto expected = brute.nearest_hit(ray, {0, kInfinity}, counts);
        const auto found = world.nearest_hit(ray, {0, kInfinity}, counts);
        ASSERT_EQ(found.has_value(), expected.has_value());
        if (!found) {
            ASSERT_FALSE(world.occluded(ray, {0, kInfinity}, counts));
            continue;
        }
        ++hits;
        instance_hits += world.objects()[found->object].kind == ObjectKind::MeshInstance;
        // The same test on the same ray, but GCC may fuse a multiply-add at one call site and
        // not at the other (-ffp-contract=fast; turning it off costs 8% on task2), here when
        // carrying a ray into an instance: the ray moves by an ulp of the scene's size (~1), so
        // t by about as much, whatever its own size.
        ASSERT_NEAR(found->t, expected->t, 1e-14 * std::max(expected->t, Real(1)));
        ASSERT_EQ(found->object, expected->object);
        const SurfaceHit a = world.surface(ray, *found), b = brute.surface(ray, *expected);
        ASSERT_LT(glm::length(a.normal - b.normal), 1e-12);
        ASSERT_EQ(a.material, b.material);
        // Any hit over a random part of the ray: blocked exactly when the nearest hit lies in it.
        const Interval part{0, found->t * fraction(random)};
        ASSERT_EQ(world.occluded(ray, part, counts), part.contains(found->t));
        ASSERT_EQ(brute.occluded(ray, part, counts), part.contains(found->t));
    }
    EXPECT_GT(hits, int(sweep(30000)));
    EXPECT_GT(instance_hits, int(sweep(3000)));
}

// The shadow cache (occluded with the shape that blocked an earlier ray) gives every answer
// that the search alone gives, for the BVH's top level and for the objects one by one, and
// answers from the cache where neighbouring rays share their blocker.
TEST(World, ShadowCacheChangesNoAnswer) {
    for (Accelerator accel : {Accelerator::Sah, Accelerator::None}) {
        const MixedScene mixed = mixed_scene(400, 6, accel);
        const World world(mixed.scene, mixed.meshes);
        std::mt19937 random(9);
        std::uniform_real_distribution<double> fraction(0, 1.5), jitter(-1e-3, 1e-3);
        Occluder last;
        int blocked = 0, from_cache = 0;
        for (const Ray& first : random_rays(20000, 8)) {
            // Each ray, then a neighbour of it (as the next pixel's shadow ray).
            const Ray next{first.origin, glm::normalize(first.direction + Vec3(jitter(random), jitter(random), 0))};
            for (const Ray& ray : {first, next}) {
                const Interval part{0, Real(10 * fraction(random))};
                SearchCounts plain, cached;
                const bool expected = world.occluded(ray, part, plain);
                const Occluder before = last;
                ASSERT_EQ(world.occluded(ray, part, cached, last), expected) << "accel " << int(accel);
                if (!expected) continue;
                ++blocked;
                // Answered by the cached shape alone: a sphere or one run of triangles, no box.
                auto by_cache = [](const Occluder& o, const SearchCounts& c) {
                    return o.entry != Occluder::kNone && c.objects.box_tests + c.triangles.box_tests == 0 &&
                           c.objects.primitive_tests + c.triangles.primitive_tests <= kTriangleLanes;
                };
                from_cache += by_cache(before, cached);
                // A shape the search recorded blocks the ray by itself (planes are not recorded).
                const bool recorded_now = last.entry != before.entry ||
                                          last.triangles.first != before.triangles.first ||
                                          last.triangles.count != before.triangles.count;
                if (last.entry != Occluder::kNone && recorded_now) {
                    Occluder recorded = last;
                    SearchCounts again;
                    ASSERT_TRUE(world.occluded(ray, part, again, recorded));
                    ASSERT_TRUE(by_cache(last, again));
                }
            }
        }
        EXPECT_GT(blocked, int(sweep(4000))) << "accel " << int(accel);
        EXPECT_GT(from_cache, blocked / 20) << "accel " << int(accel);
    }
}

// Against every primitive placed in world coordinates, without World (3 10^4 rays, as it is
// slow): the same objects and t up to the rounding of carrying rays into an instance's
// coordinates. Also with every mesh block flattened into one placed mesh.
TEST(World, TwoLevelSearchAgreesWithTestingEveryPlacedTriangle) {
    const MixedScene mixed = mixed_scene(400, 4);
    const BruteForce brute(mixed);
    for (bool flatten : {false, true}) {
        const World world(mixed.scene, mixed.meshes, 0, flatten);
        ASSERT_EQ(world.meshes().size(), flatten ? 1u : 3u);
        int rays = 0, hits = 0, disagreements = 0;
        for (const Ray& ray : random_rays(30000, 5)) {
            ++rays;
            SearchCounts counts;
            const BruteHit expected = brute.nearest(ray, {0, kInfinity});
            const auto found = world.nearest_hit(ray, {0, kInfinity}, counts);
            if (found.has_value() != expected.found) {
                ++disagreements;  // a ray grazing an edge, decided otherwise after the transform's rounding
                continue;
            }
            if (!found) continue;
            ++hits;
            if (found->object != expected.object) {
                ++disagreements;
                continue;
            }
            ASSERT_NEAR(found->t, expected.t, 1e-9 * expected.t) << "flatten " << flatten;
            EXPECT_EQ(world.occluded(ray, {0, expected.t * (1 - 1e-9)}, counts), false);
            EXPECT_EQ(world.occluded(ray, {0, expected.t * (1 + 1e-9)}, counts), true);
        }
        EXPECT_GT(hits, int(sweep(9000)));
        ::testing::Test::RecordProperty(flatten ? "disagreements_flattened" : "disagreements", disagreements);
        EXPECT_LE(disagreements, 2) << "of " << rays << " rays, flatten " << flatten;
    }
}

// An instance's shading normal is the one the same mesh gets when built placed in the world,
// also under a non-uniform scale: the area-weighted normals carried by the inverse transpose
// are those of the placed mesh, and they are interpolated after being carried.
TEST(World, InstanceNormalsMatchTheMeshBuiltPlaced) {
    SceneDescription scene;
    scene.materials.resize(1);
    Mesh block;
    block.scale = dvec3(0.3, 0.2, 0.45);
    block.rotate_axis = glm::normalize(dvec3(1, 2, 3));
    block.rotate_degrees = 70;
    block.translate = {0.5, -0.2, 0.1};
    scene.meshes = {block};
    const SceneMeshes once{{share_mesh(read("bunny.obj"))}, {0}};
    const World placed(scene, once);
    scene.meshes.push_back(block);
    scene.meshes.back().translate.x += 100;  // out of the way
    const World instanced(scene, SceneMeshes{once.files, {0, 0}});
    ASSERT_TRUE(placed.instances()[0].placed);
    ASSERT_FALSE(instanced.instances()[0].placed);
    int hits = 0, disagreements = 0;
    for (const Ray& ray : random_rays(20000, 6)) {
        SearchCounts counts;
        const auto a = nearest_surface(placed, ray, {0, kInfinity}, counts),
                   b = nearest_surface(instanced, ray, {0, kInfinity}, counts);
        if (a.has_value() != b.has_value()) ++disagreements;  // grazing an edge: rounding decides
        if (!a || !b) continue;
        ++hits;
        ASSERT_NEAR(a->t, b->t, 1e-9 * a->t);
        ASSERT_LT(glm::length(a->normal - b->normal), 1e-9);
    }
    EXPECT_LE(disagreements, 2);
    EXPECT_GT(hits, int(sweep(500)));
}

// A cube of 8 shared corners without normals: smooth shading averages the three faces at each
// corner (a cushion); `shading flat` gives each face its own normal, placed or instanced, and
// a file used both ways is built once for each.
TEST(World, FlatShadingGivesEachTriangleItsOwnNormal) {
    TriangleMesh cube;
    for (int i = 0; i < 8; ++i) cube.positions.push_back({i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0});
    // Two triangles per face, wound outwards.
    const uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : faces) {
        cube.triangles.push_back({f[0], f[1], f[2]});
        cube.triangles.push_back({f[0], f[2], f[3]});
    }
    SceneDescription scene;
    scene.materials.resize(1);
    Mesh block;
    scene.meshes = {block};
    const Ray towards_the_top_face{{0.5, 5, 0.3}, {0, -1, 0}};
    SearchCounts counts;
    const auto smooth = nearest_surface(World(scene, SceneMeshes{{share_mesh(cube)}, {0}}), towards_the_top_face,
                                        {0, kInfinity}, counts);
    ASSERT_TRUE(smooth);
    EXPECT_GT(glm::length(smooth->normal - Vec3(0, 1, 0)), 0.1);  // the corners' averages lean outwards
    scene.meshes[0].flat = true;
    const auto flat = nearest_surface(World(scene, SceneMeshes{{share_mesh(cube)}, {0}}), towards_the_top_face,
                                      {0, kInfinity}, counts);
    ASSERT_TRUE(flat);
    EXPECT_EQ(flat->normal, Vec3(0, 1, 0));
    // Instanced: two flat blocks and one smooth block of the same file.
    scene.meshes = {scene.meshes[0], scene.meshes[0], block};
    scene.meshes[1].translate = {10, 0, 0};
    scene.meshes[2].translate = {20, 0, 0};
    const World both(scene, SceneMeshes{{share_mesh(cube)}, {0, 0, 0}});
    EXPECT_EQ(both.meshes().size(), 2u);
    const auto flat_instance = nearest_surface(both, towards_the_top_face, {0, kInfinity}, counts);
    ASSERT_TRUE(flat_instance);
    EXPECT_LT(glm::length(flat_instance->normal - Vec3(0, 1, 0)), 1e-12);
    const Ray towards_the_smooth_one{{20.5, 5, 0.3}, {0, -1, 0}};
    const auto smooth_instance = nearest_surface(both, towards_the_smooth_one, {0, kInfinity}, counts);
    ASSERT_TRUE(smooth_instance);
    EXPECT_LT(glm::length(smooth_instance->normal - smooth->normal), 1e-12);
}

// A mesh file named by many blocks is read once and built once; every extra instance costs a
// few hundred bytes, not a copy of the mesh.
TEST(World, InstancesShareOneMesh) {
    SceneDescription scene;
    scene.materials.resize(1);
    const std::string bunny = (kMeshes / "bunny.obj").string();
    for (int i = 0; i < 4096; ++i) {
        Mesh block;
        block.path = bunny;
        block.translate = {i % 64, 0, i / 64};
        block.rotate_degrees = i;
        scene.meshes.push_back(block);
    }
    Diagnostics diagnostics;
    const auto meshes = load_meshes(scene, diagnostics);
    ASSERT_TRUE(meshes);
    ASSERT_EQ(meshes->files.size(), 1u);
    const World many(scene, *meshes);
    ASSERT_EQ(many.meshes().size(), 1u);
    ASSERT_EQ(many.instances().size(), 4096u);
    scene.meshes.resize(1);
    const World one(scene, SceneMeshes{meshes->files, {0}});
    const size_t one_bunny = one.meshes()[0].memory_bytes() + one.top_level_memory_bytes();
    const size_t all = many.meshes()[0].memory_bytes() + many.top_level_memory_bytes();
    ::testing::Test::RecordProperty("bytes_per_instance", int((all - one_bunny) / 4095));
    EXPECT_LE(all, 2 * one_bunny + 200 * 4096);
}

// A sphere is kept once, in the top level's entry (its center, radius, object and kind), beside
// its object record and its share of the wide tree: 40,000 spheres on a grid (whose tree at leaf
// size 1 takes 0.3 wide nodes of 256 bytes per sphere) cost under 150 bytes each.
TEST(World, SpheresAreKeptOnce) {
    SceneDescription scene;
    scene.materials.resize(1);
    for (int i = 0; i < 40000; ++i) scene.spheres.push_back({{i % 200, i / 200, 0}, 0.4, 0});
    const World world(scene, SceneMeshes{});
    ASSERT_FALSE(world.top_level_linear());
    const size_t per_sphere = world.top_level_memory_bytes() / 40000;
    ::testing::Test::RecordProperty("bytes_per_sphere", int(per_sphere));
    EXPECT_LE(per_sphere, 150u);
}

// From 2^19 bounded objects on, the top level gathers a few spheres into each leaf: under 80
// bytes a sphere, and the same nearest hits as testing every sphere one by one.
TEST(World, HugeTopLevelsGatherSpheresIntoLeaves) {
    constexpr int kSide = 730;  // 532,900 spheres
    SceneDescription scene;
    scene.materials.resize(1);
    for (int i = 0; i < kSide * kSide; ++i) scene.spheres.push_back({{i % kSide, i / kSide, 0}, 0.4, 0});
    SceneDescription linear = scene;
    linear.render.accel = Accelerator::None;
    const World world(scene, SceneMeshes{}), brute(linear, SceneMeshes{});
    ASSERT_FALSE(world.top_level_linear());
    EXPECT_LT(world.top_level().stats().leaves, size_t(kSide) * kSide / 2);
    const size_t per_sphere = world.top_level_memory_bytes() / (size_t(kSide) * kSide);
    ::testing::Test::RecordProperty("bytes_per_sphere", int(per_sphere));
    EXPECT_LE(per_sphere, 80u);
    std::mt19937 random(9);
    std::uniform_real_distribution<double> unit(0, 1);
    int hits = 0;
    for (int i = 0; i < 100; ++i) {
        const Ray ray{Vec3(kSide * unit(random), kSide * unit(random), 3),
                      Vec3(glm::normalize(glm::dvec3(unit(random) - 0.5, unit(random) - 0.5, -1)))};
        SearchCounts counts;
        const auto a = world.nearest_hit(ray, {0, kInfinity}, counts);
        const auto b = brute.nearest_hit(ray, {0, kInfinity}, counts);
        ASSERT_EQ(a.has_value(), b.has_value()) << "ray " << i;
        if (!a) continue;
        ++hits;
        EXPECT_EQ(a->object, b->object) << "ray " << i;
        // To a few ulps: the one-by-one search's sphere test is inlined elsewhere, and the
        // compiler fuses its multiply-adds differently there.
        EXPECT_NEAR(a->t, b->t, 64 * std::numeric_limits<Real>::epsilon() * a->t) << "ray " << i;
    }
    EXPECT_GT(hits, 30);
}

}  // namespace
}  // namespace tracer
