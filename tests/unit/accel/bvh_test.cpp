// Every accelerator must find exactly what testing every triangle finds: the same nearest
// triangle at the same t, and the same answer to "is anything in the way".
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <optional>
#include <random>

#include <glm/geometric.hpp>

#include "../../common/flat_grid.h"
#include "../../common/sweep.h"
#include "accel/mesh_accel.h"
#include "accel/world.h"
#include "io/obj_mesh.h"

namespace tracer {
namespace {

TriangleMesh bunny() {
    Mesh placement;
    placement.path = (std::filesystem::path(TRACER_SOURCE_DIR) / "scenes" / "meshes" / "bunny.obj").string();
    Diagnostics diagnostics;
    auto mesh = load_mesh(placement, diagnostics);
    EXPECT_TRUE(mesh) << "cannot load bunny.obj";
    return mesh ? *mesh : TriangleMesh{};
}

// The mesh in its own coordinates: brute force (no build given) or behind a BVH.
MeshAccel accel(const TriangleMesh& mesh, std::optional<BvhBuild> build, int leaf_size) {
    SearchSettings settings;
    settings.brute_force = !build;
    settings.build = build.value_or(BvhBuild::Sah);
    settings.leaf_size = leaf_size;
    return MeshAccel(mesh, Placement(), settings);
}

const char* build_name(BvhBuild build) {
    return build == BvhBuild::Box ? "box" : build == BvhBuild::Median ? "median" : "sah";
}

// Random triangles of very different sizes, overlapping and intersecting each other.
TriangleMesh triangle_soup(int count, uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(0, 1);
    TriangleMesh soup;
    for (int i = 0; i < count; ++i) {
        const Vec3 center(unit(random), unit(random), unit(random));
        const double size = 0.002 + 0.2 * unit(random) * unit(random);
        const uint32_t first = uint32_t(soup.positions.size());
        for (int k = 0; k < 3; ++k)
            soup.positions.push_back(glm::dvec3(center) +
                                     size * glm::dvec3(unit(random) - 0.5, unit(random) - 0.5, unit(random) - 0.5));
        soup.triangles.push_back({first, first + 1, first + 2});
    }
    return soup;
}

struct Agreement {
    int rays = 0, hits = 0, ties = 0;
};

// `rays` rays from a sphere around the mesh towards random points of its bounding box, each
// traced by brute force and by box, median and sah.
void compare_with_brute_force(const TriangleMesh& mesh, uint32_t seed, int rays, Agreement& result) {
    const MeshAccel brute = accel(mesh, std::nullopt, 1);
    const BvhBuild builds[] = {BvhBuild::Box, BvhBuild::Median, BvhBuild::Sah};
    const MeshAccel trees[] = {accel(mesh, builds[0], 3), accel(mesh, builds[1], 3), accel(mesh, builds[2], 3)};
    Bounds box;
    for (const auto& p : mesh.positions) box.extend(Vec3(p));
    const Vec3 center = box.center();
    const double radius = glm::length(box.upper - box.lower);
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(0, 1);
    std::normal_distribution<double> gauss;
    for (int i = 0; i < rays && !::testing::Test::HasFailure(); ++i) {
        const Vec3 on_sphere = glm::normalize(Vec3(gauss(random), gauss(random), gauss(random)));
        const Vec3 origin = center + Real(radius) * on_sphere;
        const Vec3 target = box.lower + Vec3(unit(random), unit(random), unit(random)) * (box.upper - box.lower);
        const Ray ray{origin, glm::normalize(target - origin)};
        TraversalCounts counts;
        Interval brute_range{0, kInfinity};
        MeshHit brute_hit;
        const bool brute_found = brute.intersect(ray, brute_range, brute_hit, counts);
        const double fraction = 2 * unit(random);
        ++result.rays;
        result.hits += brute_found;
        for (int k = 0; k < 3; ++k) {
            const MeshAccel& tree = trees[k];
            const char* name = build_name(builds[k]);
            Interval tree_range{0, kInfinity};
            MeshHit tree_hit;
            const bool tree_found = tree.intersect(ray, tree_range, tree_hit, counts);
            ASSERT_EQ(tree_found, brute_found) << name << ", ray " << i;
            if (!brute_found) continue;
            ASSERT_EQ(tree_hit.hit.t, brute_hit.hit.t) << name << ", ray " << i;
            if (tree.triangle_of(tree_hit.slot) != brute.triangle_of(brute_hit.slot))
                ++result.ties;  // two triangles at the very same t
            // Any-hit over a random part of the ray agrees with "the nearest hit lies inside it".
            const Interval part{0, brute_hit.hit.t * fraction};
            ASSERT_EQ(tree.occluded(ray, part, counts), part.contains(brute_hit.hit.t)) << name << ", ray " << i;
        }
    }
}

TEST(Bvh, EveryAcceleratorAgreesWithBruteForceOnTheBunny) {
    Agreement a;
    compare_with_brute_force(bunny(), 1, int(sweep(100000)), a);  // fewer under the sanitizers
    EXPECT_GT(a.hits, a.rays * 3 / 10);                           // the rays really do hit the mesh
    EXPECT_LT(a.ties, 10);
}

TEST(Bvh, EveryAcceleratorAgreesWithBruteForceOnATriangleSoup) {
    Agreement a;
    compare_with_brute_force(triangle_soup(3000, 7), 2, int(sweep(100000)), a);
    EXPECT_GT(a.hits, a.rays * 3 / 10);
    EXPECT_LT(a.ties, 10);
}

// Meshes so small that the tree is one leaf, or a root whose children are all leaves.
TEST(Bvh, EveryAcceleratorAgreesWithBruteForceOnTinyMeshes) {
    for (int count : {1, 2, 5, 9}) {
        Agreement a;
        compare_with_brute_force(triangle_soup(count, 20 + count), 3, 100000, a);  // few hit: every ray
        EXPECT_GT(a.hits, 50) << count << " triangles";  // small triangles far apart: ~0.1% of the rays hit
    }
}

// hard-cases.md A3: 64 x 64 unit squares in z = 0 (8,192 triangles), so every BVH box has zero
// thickness, and rays along the grid lines, where slab tests meet 0 * infinity. The trees must
// lose no hit that testing every triangle finds. (That every ray hits at all is a property of
// the triangle test: the watertight one lets none through, Moller-Trumbore lets 24 rays through
// exact grid vertices slip between triangles.)
TEST(Bvh, FlatGridTraversalLosesNoHitOfTheTriangleTest) {
    const TriangleMesh grid = flat_grid();
    const MeshAccel brute = accel(grid, std::nullopt, 1);
    for (BvhBuild build : {BvhBuild::Median, BvhBuild::Sah}) {
        const MeshAccel tree = accel(grid, build, 3);
        int rays = 0, hits = 0;
        // (a) straight down from (0.5 a, 0.5 b, 1): 16,641 rays, 12,545 of them on grid lines;
        // once with direction (0, 0, -1) and once with (-0, -0, -1), whose negative zeros must
        // not turn the slabs around.
        for (double zero : {0.0, -0.0}) {
            for (int a = 0; a <= 128; ++a)
                for (int b = 0; b <= 128; ++b) {
                    const Ray ray{{0.5 * a, 0.5 * b, 1.0}, {zero, zero, -1.0}};
                    Interval range{0, kInfinity}, brute_range{0, kInfinity};
                    MeshHit hit, brute_hit;
                    TraversalCounts counts;
                    ++rays;
                    const bool found = tree.intersect(ray, range, hit, counts);
                    if (in_sweep(size_t(rays))) {  // the cross-check of a fraction under the sanitizers
                        EXPECT_EQ(found, brute.intersect(ray, brute_range, brute_hit, counts))
                            << build_name(build) << " at " << a << ", " << b;
                    }
                    if (!found) continue;
                    ++hits;
                    EXPECT_EQ(hit.hit.t, 1.0) << build_name(build) << " at " << a << ", " << b;
                }
        }
        // (b) towards every interior vertex from v + (-0.3, 0.2, 5).
        for (int j = 1; j < 64; ++j)
            for (int i = 1; i < 64; ++i) {
                const Vec3 v(i, j, 0), origin = v + Vec3(-0.3, 0.2, 5);
                const Ray ray{origin, glm::normalize(v - origin)};
                Interval tree_range{0, kInfinity}, brute_range{0, kInfinity};
                MeshHit tree_hit, brute_hit;
                TraversalCounts counts;
                ++rays;
                const bool found = tree.intersect(ray, tree_range, tree_hit, counts);
                hits += found;
                if (!in_sweep(size_t(rays))) continue;  // the cross-check of a fraction under the sanitizers
                EXPECT_EQ(found, brute.intersect(ray, brute_range, brute_hit, counts));
                if (found) {
                    EXPECT_EQ(tree_hit.hit.t, brute_hit.hit.t);
                }
            }
        // The watertight test lets no ray through; Moller-Trumbore lets 24 slip between triangles.
        EXPECT_GE(hits, kRobust ? rays : rays - 24) << build_name(build);
        ::testing::Test::RecordProperty(std::string("misses_") + build_name(build), rays - hits);
    }
}

// The bounding-sphere pre-tests (World::may_hit, and the one before each mesh instance) must
// not reject rays that only just hit: a square's corners lie on the sphere around its box, so rays aimed just inside
// the corners, from near and from very far, at several scales and offsets, graze that sphere.
TEST(Bvh, SpherePreTestKeepsRaysThatGrazeTheMeshCorners) {
    std::mt19937 random(5);
    std::normal_distribution<double> gauss;
    int hits = 0;
    for (double scale : {1e-3, 1.0, 1e3})
        for (double offset : {0.0, 1e4}) {
            TriangleMesh square;
            for (Vec3 corner : {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)})
                square.positions.push_back(glm::dvec3(offset) + scale * glm::dvec3(corner));
            square.triangles = {{0, 1, 2}, {0, 2, 3}};
            const MeshAccel brute = accel(square, std::nullopt, 1);
            SceneDescription scene;
            scene.meshes.resize(1);
            const World world(scene, SceneMeshes{{share_mesh(square)}, {0}});
            for (int corner = 0; corner < 4; ++corner) {
                const Vec3 inward = glm::normalize(
                    Vec3(glm::dvec3(0.5, 0.5, 0) * scale + glm::dvec3(offset) - square.positions[corner]));
                const Vec3 target = Vec3(square.positions[corner]) + inward * Real(1e-7 * scale);
                for (double distance : {10.0, 1e6})
                    for (int i = 0; i < 50; ++i) {
                        Vec3 from = glm::normalize(Vec3(gauss(random), gauss(random), gauss(random)));
                        from.z = std::abs(from.z) + 0.05;  // not in the plane of the square
                        const Ray ray{target + Real(distance * scale) * glm::normalize(from), -glm::normalize(from)};
                        TraversalCounts counts;
                        SearchCounts world_counts;
                        Interval brute_range;
                        MeshHit brute_hit;
                        const bool found = brute.intersect(ray, brute_range, brute_hit, counts);
                        hits += found;
                        ASSERT_EQ(world.may_hit(ray) && world.nearest_hit(ray, {0, kInfinity}, world_counts), found);
                        ASSERT_EQ(world.may_hit(ray) && world.occluded(ray, {0, kInfinity}, world_counts), found);
                    }
            }
        }
    EXPECT_GT(hits, 2000);  // of 2,400: the rays do hit, at the very edge of the sphere
}

TEST(Bvh, MedianFollowsTheAssignment) {
    // Leaves hold at most leaf_size triangles; the tree splits x, y, z by depth.
    const MeshAccel median = accel(bunny(), BvhBuild::Median, 3);
    const BvhStats stats = median.bvh().stats();
    EXPECT_LE(stats.max_leaf, 3u);
    EXPECT_EQ(stats.nodes, 2 * stats.leaves - 1);
    EXPECT_LE(stats.depth, 13);  // a balanced tree: ceil(log2(3674 / 2)) + 1
}

TEST(Bvh, SahLeavesNeverExceedTheLeafSize) {
    for (int leaf : {1, 3, 8}) {
        const MeshAccel sah = accel(bunny(), BvhBuild::Sah, leaf);
        EXPECT_LE(sah.bvh().stats().max_leaf, size_t(leaf));
    }
}

TEST(Bvh, LeavesContainTheirTriangles) {
    const TriangleMesh soup = triangle_soup(500, 3);
    for (BvhBuild method : {BvhBuild::Median, BvhBuild::Sah}) {
        const MeshAccel tree = accel(soup, method, 3);
        std::vector<int> seen(soup.triangles.size(), 0);  // how many leaves hold each triangle
        tree.bvh().for_each_leaf([&](const Bounds& box, uint32_t first, uint32_t count, int) {
            for (uint32_t i = first; i < first + count; ++i) {
                ++seen[tree.triangle_of(i)];
                for (uint32_t v : soup.triangles[tree.triangle_of(i)])
                    for (int axis = 0; axis < 3; ++axis) {
                        EXPECT_LE(box.lower[axis], soup.positions[v][axis]);
                        EXPECT_GE(box.upper[axis], soup.positions[v][axis]);
                    }
            }
        });
        EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), std::ptrdiff_t(soup.triangles.size())) << build_name(method);
    }
}

// Each build keeps one tree layout, and searches pass to it: Sah a WideBvh, Box and Median a
// BinaryBvh; no primitives make an empty binary tree, which nothing enters.
TEST(Bvh, EachBuildKeepsOneLayout) {
    LargeArray<Bounds> boxes(64);
    for (uint32_t i = 0; i < 64; ++i) {
        boxes[i] = Bounds{};
        boxes[i].extend(Vec3(i, 0, 0));
        boxes[i].extend(Vec3(i + 0.5, 1, 1));
    }
    for (BvhBuild method : {BvhBuild::Box, BvhBuild::Median, BvhBuild::Sah}) {
        const Bvh bvh(boxes, method, 2);
        EXPECT_EQ(bvh.wide() != nullptr, method == BvhBuild::Sah) << build_name(method);
        EXPECT_EQ(bvh.binary() != nullptr, method != BvhBuild::Sah) << build_name(method);
        // A ray along x from the left meets box 0 first, whichever tree searches.
        const Ray ray{Vec3(-1, 0.5, 0.5), Vec3(1, 0, 0)};
        Interval range{0, kInfinity};
        TraversalCounts counts;
        std::optional<uint32_t> nearest;
        const bool hit = bvh.closest(ray, range, counts, [&](uint32_t entry, Interval& r) {
            const Real t = Real(bvh.order()[entry]) + 1;  // where the ray enters box order()[entry]
            if (t < r.min || t > r.max) return false;
            r.max = t, nearest = bvh.order()[entry];
            return true;
        });
        EXPECT_TRUE(hit) << build_name(method);
        EXPECT_EQ(nearest, 0u) << build_name(method);
        EXPECT_GT(counts.box_tests, 0u) << build_name(method);
    }
    const Bvh empty(LargeArray<Bounds>(), BvhBuild::Sah, 2);
    ASSERT_NE(empty.binary(), nullptr);
    EXPECT_TRUE(empty.binary()->nodes().empty());
    Interval range{0, kInfinity};
    TraversalCounts counts;
    EXPECT_FALSE(empty.closest(Ray{Vec3(0), Vec3(1, 0, 0)}, range, counts, [](uint32_t, Interval&) { return true; }));
}

// Sah's wide nodes: every inner child's box holds its node's children's boxes.
TEST(Bvh, WideNodesContainTheirChildren) {
    const MeshAccel sah = accel(triangle_soup(2000, 5), BvhBuild::Sah, 1);
    ASSERT_NE(sah.bvh().wide(), nullptr);
    const auto& wide = sah.bvh().wide()->nodes();
    ASSERT_GT(wide.size(), 1u);
    size_t inner = 0;
    for (const WideNode& node : wide)
        for (int lane = 0; lane < kWide; ++lane) {
            if (node.count[lane] != WideNode::kInner) continue;
            ++inner;
            const WideNode& child = wide[node.index[lane]];
            for (int k = 0; k < kWide; ++k) {
                if (child.count[k] == 0) continue;  // no child in this lane
                for (int axis = 0; axis < 3; ++axis) {
                    EXPECT_LE(node.planes[0][axis][lane], child.planes[0][axis][k]);
                    EXPECT_GE(node.planes[1][axis][lane], child.planes[1][axis][k]);
                }
            }
        }
    EXPECT_EQ(inner, wide.size() - 1);  // every node but the root is some node's child, once
}

// The wide tree is allocated once at its exact size (counted before it is filled): a grid of
// equal boxes at leaf size 1 collapses into 0.3 nodes per box, past any fixed reserve, and a
// mesh into 0.08, far under one.
TEST(Bvh, WideTreesHoldNoUnusedNodes) {
    for (uint32_t side : {40u, 300u}) {
        LargeArray<Bounds> boxes(size_t(side) * side);
        for (uint32_t i = 0; i < side * side; ++i) {
            boxes[i] = Bounds{};
            boxes[i].extend(Vec3(i % side, i / side, 0));
            boxes[i].extend(Vec3(i % side + 0.8, i / side + 0.8, 0.8));
        }
        for (int leaf_size : {1, 4}) {
            const Bvh bvh(boxes, BvhBuild::Sah, leaf_size, 2);
            EXPECT_EQ(bvh.wide()->nodes().capacity(), bvh.wide()->nodes().size())
                << side << ", leaf size " << leaf_size;
        }
    }
}

// LeafGathering: subtrees of at most `most` gatherable primitives become one leaf; every
// primitive stays in exactly one leaf, inside its box; others keep leaves of the leaf size;
// the tree has fewer nodes, and its nearest hits are those of the ungathered tree.
TEST(Bvh, GatheredLeavesHoldSmallSubtreesOfGatherablePrimitives) {
    constexpr uint32_t kSide = 120, kMost = 6;
    LargeArray<Bounds> boxes(size_t(kSide) * kSide);
    for (uint32_t i = 0; i < kSide * kSide; ++i) {
        boxes[i] = Bounds{};
        boxes[i].extend(Vec3(i % kSide, i / kSide, 0));
        boxes[i].extend(Vec3(i % kSide + 0.8, i / kSide + 0.8, 0.8));
    }
    auto gatherable = [](uint32_t id) { return id % 7 != 0; };  // every seventh may not be gathered
    const Bvh plain(boxes, BvhBuild::Sah, 1, 2);
    const Bvh gathered(boxes, BvhBuild::Sah, 1, 2, 1, LeafGathering{kMost, gatherable});
    std::vector<int> seen(boxes.size(), 0);
    int gathered_leaves = 0;
    gathered.for_each_leaf([&](const Bounds& box, uint32_t first, uint32_t count, int) {
        EXPECT_LE(count, kMost);
        gathered_leaves += count > 1;
        for (uint32_t k = first; k < first + count; ++k) {
            const uint32_t id = gathered.order()[k];
            ++seen[id];
            if (count > 1) {
                EXPECT_TRUE(gatherable(id)) << id;
            }
            for (int axis = 0; axis < 3; ++axis) {
                EXPECT_LE(box.lower[axis], boxes[id].lower[axis]);
                EXPECT_GE(box.upper[axis], boxes[id].upper[axis]);
            }
        }
    });
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), std::ptrdiff_t(boxes.size()));
    EXPECT_GT(gathered_leaves, 500);
    EXPECT_LT(gathered.wide()->nodes().size(), plain.wide()->nodes().size() * 2 / 3);
    EXPECT_EQ(gathered.wide()->nodes().capacity(), gathered.wide()->nodes().size());
    std::mt19937 random(3);
    std::uniform_real_distribution<double> unit(0, 1);
    int hits = 0;
    for (int i = 0; i < 2000; ++i) {
        const Ray ray{Vec3(kSide * unit(random), kSide * unit(random), 5),
                      Vec3(glm::normalize(glm::dvec3(unit(random) - 0.5, unit(random) - 0.5, -1)))};
        auto nearest = [&](const Bvh& bvh) {
            Interval range{0, kInfinity};
            TraversalCounts counts;
            uint32_t found = ~0u;
            bvh.closest(ray, range, counts, [&](uint32_t k, Interval& r) {
                const Bounds& box = boxes[bvh.order()[k]];
                const float t = (float(box.upper.z) - float(ray.origin.z)) / float(ray.direction.z);
                const Vec3 p = ray.at(t);
                if (!(r.contains(t) && p.x >= box.lower.x && p.x <= box.upper.x && p.y >= box.lower.y &&
                      p.y <= box.upper.y))
                    return false;
                r.max = t, found = bvh.order()[k];
                return true;
            });
            return found;
        };
        const uint32_t a = nearest(plain), b = nearest(gathered);
        EXPECT_EQ(a, b) << "ray " << i;
        hits += a != ~0u;
    }
    EXPECT_GT(hits, 1000);
}

// Large inputs are built on several threads (subtrees, and the root's binning and
// partitioning, in parallel): the tree must be the one a single thread builds, holding every
// primitive once, each inside its leaf's box.
TEST(Bvh, ParallelBuildsMakeTheSingleThreadedTree) {
    std::mt19937 random(11);
    std::uniform_real_distribution<double> unit(0, 1);
    LargeArray<Bounds> boxes(150000);  // three times the size from which builds go parallel
    for (Bounds& box : boxes) {
        const Vec3 corner(unit(random), unit(random), unit(random));
        box.extend(corner);
        box.extend(corner + Real(0.01) * Vec3(unit(random), unit(random), unit(random)));
    }
    for (BvhBuild method : {BvhBuild::Median, BvhBuild::Sah}) {
        const char* name = build_name(method);
        const Bvh serial(boxes, method, 3, 1), parallel(boxes, method, 3, 2);
        // The same nodes, byte for byte (the nodes hold no padding).
        auto same_bytes = [](const auto& a, const auto& b) {
            return a.size() == b.size() &&
                   (a.size() == 0 || std::memcmp(a.data(), b.data(), a.size() * sizeof a[0]) == 0);
        };
        ASSERT_EQ(serial.wide() != nullptr, method == BvhBuild::Sah) << name;
        if (serial.wide()) {
            ASSERT_TRUE(same_bytes(serial.wide()->nodes(), parallel.wide()->nodes())) << name;
            ASSERT_GT(serial.wide()->nodes().size(), 1000u) << name;
        } else {
            ASSERT_TRUE(same_bytes(serial.binary()->nodes(), parallel.binary()->nodes())) << name;
            ASSERT_GT(serial.binary()->nodes().size(), 1000u) << name;
        }
        // The same primitives in each leaf (partitioning in halves may order them otherwise),
        // every one inside its leaf's box.
        struct Leaf {
            Bounds box;
            std::vector<uint32_t> ids;
        };
        auto leaves = [](const Bvh& bvh) {
            std::vector<Leaf> all;
            bvh.for_each_leaf([&](const Bounds& box, uint32_t first, uint32_t count, int) {
                all.push_back({box, {bvh.order().begin() + first, bvh.order().begin() + first + count}});
                std::sort(all.back().ids.begin(), all.back().ids.end());
            });
            return all;
        };
        const std::vector<Leaf> serial_leaves = leaves(serial), parallel_leaves = leaves(parallel);
        ASSERT_EQ(serial_leaves.size(), parallel_leaves.size()) << name;
        std::vector<int> seen(boxes.size(), 0);
        for (size_t k = 0; k < parallel_leaves.size(); ++k) {
            const Leaf& leaf = parallel_leaves[k];
            ASSERT_EQ(leaf.ids, serial_leaves[k].ids) << name << ", leaf " << k;
            for (uint32_t id : leaf.ids) {
                ++seen[id];
                for (int axis = 0; axis < 3; ++axis) {
                    ASSERT_LE(leaf.box.lower[axis], boxes[id].lower[axis]);
                    ASSERT_GE(leaf.box.upper[axis], boxes[id].upper[axis]);
                }
            }
        }
        EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), std::ptrdiff_t(boxes.size())) << name;
    }
}

// Sah's wide tree built directly (from kDirectWideFrom primitives) is the tree collapsed from
// the binary build, byte for byte, on one thread and on two: for scattered boxes, for boxes
// whose centers all coincide (split in halves), for one and two boxes, and with small subtrees
// gathered into leaves (whose entries the binary build orders otherwise: compared as sets).
TEST(Bvh, DirectWideBuildsMakeTheCollapsedTree) {
    std::mt19937 random(5);
    std::uniform_real_distribution<double> unit(0, 1);
    auto scattered = [&](size_t count) {
        LargeArray<Bounds> boxes(count);
        for (Bounds& box : boxes) {
            const Vec3 corner(unit(random), unit(random), unit(random) * 0.1);
            box = Bounds{};
            box.extend(corner);
            box.extend(corner + Real(0.02) * Vec3(unit(random), unit(random), unit(random)));
        }
        return boxes;
    };
    LargeArray<Bounds> same(300);
    for (Bounds& box : same) box = Bounds{}, box.extend(Vec3(1, 2, 3)), box.extend(Vec3(2, 3, 4));
    const std::vector<LargeArray<Bounds>> inputs{scattered(20000), scattered(1), scattered(2), same};
    const LeafGathering none, some{6, [](uint32_t id) { return id % 5 != 0; }};
    auto leaf_sets = [](const Bvh& bvh) {
        std::vector<std::vector<uint32_t>> sets;
        bvh.for_each_leaf([&](const Bounds&, uint32_t first, uint32_t count, int) {
            sets.emplace_back(bvh.order().begin() + first, bvh.order().begin() + first + count);
            std::sort(sets.back().begin(), sets.back().end());
        });
        return sets;
    };
    for (const LargeArray<Bounds>& boxes : inputs)
        for (int threads : {1, 2})
            for (const LeafGathering* gathering : {&none, &some}) {
                const Bvh direct(boxes, BvhBuild::Sah, 4, threads, 4, *gathering, 0);
                const Bvh collapsed(boxes, BvhBuild::Sah, 4, threads, 4, *gathering, ~uint32_t(0));
                const auto &a = direct.wide()->nodes(), &b = collapsed.wide()->nodes();
                ASSERT_EQ(a.size(), b.size()) << boxes.size() << " boxes, " << threads << " threads";
                EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof a[0]), 0) << boxes.size() << " boxes";
                if (gathering == &none) {
                    EXPECT_EQ(direct.order(), collapsed.order()) << boxes.size() << " boxes";
                }
                EXPECT_EQ(leaf_sets(direct), leaf_sets(collapsed)) << boxes.size() << " boxes";
            }
}

// The tree's arrays are sized by the primitives, not by the builder's work space (which has
// room for every task's chunk of node slots besides the tree): 19 and 4,096 boxes keep a few
// hundred bytes per box at most, in every build.
TEST(Bvh, SmallTreesKeepSmallArrays) {
    for (uint32_t count : {19u, 4096u}) {
        for (BvhBuild method : {BvhBuild::Box, BvhBuild::Median, BvhBuild::Sah}) {
            LargeArray<Bounds> boxes(count);
            for (uint32_t i = 0; i < count; ++i) {
                boxes[i] = Bounds{};
                boxes[i].extend(Vec3(i % 64, i / 64, 0));
                boxes[i].extend(Vec3(i % 64 + 0.5, i / 64 + 0.5, 0.5));
            }
            const Bvh bvh(std::move(boxes), method, 4, 2);
            EXPECT_LE(bvh.memory_bytes(), 200 * size_t(count) + 1024) << count << " boxes, build " << int(method);
        }
    }
}

}  // namespace
}  // namespace tracer
