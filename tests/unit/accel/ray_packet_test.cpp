// Packets of rays (accel/ray_packet.h) against the same rays searched one by one: the same
// nearest hits bit for bit (triangle, t, u, v), for coherent packets
// (which take the packet search) and for packets whose rays differ in a direction's sign or
// lie along an axis (which fall back to one ray at a time).
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include <glm/geometric.hpp>

#include "accel/mesh_accel.h"
#include "accel/ray_packet.h"
#include "accel/world.h"
#include "io/obj_mesh.h"
#include "scene/placement.h"

namespace tracer {
namespace {

const std::filesystem::path kMeshes = std::filesystem::path(TRACER_SOURCE_DIR) / "scenes" / "meshes";

TriangleMesh bunny() {
    Mesh block;
    block.path = (kMeshes / "bunny.obj").string();
    Diagnostics diagnostics;
    auto mesh = load_mesh(block, diagnostics);
    EXPECT_TRUE(mesh);
    return mesh ? *mesh : TriangleMesh{};
}

// Packets of up to kPacket rays: from one eye through a small patch of view directions (as
// a tile of primary rays), from points spread over a patch towards one light (as shadow rays),
// and from anywhere in any direction. The bunny lies within about +-0.1 of (0, 0.1, 0).
std::vector<std::vector<Ray>> packets(int count, uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(0, 1);
    std::normal_distribution<double> gauss;
    auto direction = [&] { return glm::normalize(Vec3(gauss(random), gauss(random), gauss(random))); };
    std::vector<std::vector<Ray>> out;
    for (int p = 0; p < count; ++p) {
        const int size = 1 + int(unit(random) * kPacket) % kPacket;
        const Vec3 target(0.2 * unit(random) - 0.1, 0.2 * unit(random), 0.2 * unit(random) - 0.1);
        const Vec3 far_point = target + Real(0.5 + unit(random)) * direction();
        const Real spread = Real(0.001 + 0.02 * unit(random));
        std::vector<Ray> rays;
        for (int i = 0; i < size; ++i) {
            const Vec3 jitter = spread * Vec3(gauss(random), gauss(random), gauss(random));
            switch (p % 3) {
                case 0: rays.push_back({far_point, glm::normalize(target + jitter - far_point)}); break;
                case 1: rays.push_back({target + jitter, glm::normalize(far_point - target - jitter)}); break;
                default: rays.push_back({target + jitter, direction()}); break;
            }
        }
        if (p % 50 == 7) rays[0].direction = {0, 0, -1};  // along an axis: 1 / d is infinite
        out.push_back(rays);
    }
    return out;
}

TEST(RayPackets, MeshPacketsAnswerAsEachRayAlone) {
    const TriangleMesh file = bunny();
    const MeshAccel mesh(file, Placement(), SearchSettings{});
    uint64_t hits = 0, packet_boxes = 0, alone_boxes = 0;
    int index = 0;
    for (const std::vector<Ray>& rays : packets(6000, 3)) {
        const bool from_an_eye = index++ % 3 == 0;
        const int n = int(rays.size());
        const Ray* pointers[kPacket];
        Interval ranges[kPacket];
        for (int i = 0; i < n; ++i) pointers[i] = &rays[size_t(i)], ranges[i] = {0, kInfinity};
        MeshHit found[kPacket];
        TraversalCounts together, alone;
        const unsigned met = mesh.intersect_packet(pointers, n, ranges, found, together);
        for (int i = 0; i < n; ++i) {
            Interval range{0, kInfinity};
            MeshHit expected;
            const bool hit = mesh.intersect(rays[size_t(i)], range, expected, alone);
            ASSERT_EQ(bool(met >> i & 1), hit);
            if (!hit) continue;
            ++hits;
            ASSERT_EQ(found[i].slot, expected.slot);
            ASSERT_EQ(ranges[i].max, range.max);
            ASSERT_EQ(found[i].hit.t, expected.hit.t);
            ASSERT_EQ(found[i].hit.u, expected.hit.u);
            ASSERT_EQ(found[i].hit.v, expected.hit.v);
        }
        if (from_an_eye) packet_boxes += together.box_tests, alone_boxes += alone.box_tests;
    }
    EXPECT_GT(hits, 4000u);
    // The packets from an eye did go through the nodes together: far fewer box tests than alone.
    EXPECT_LT(packet_boxes * 2, alone_boxes);
}

TEST(RayPackets, WorldPacketsAnswerAsEachRayAlone) {
    // A few objects (tested one by one): spheres, a floor, the bunny placed once on its own and
    // twice more as instances of a shared file, carried into its coordinates.
    SceneDescription scene;
    scene.materials.resize(2);
    scene.spheres.push_back({{0.15, 0.1, 0}, 0.05, 0});
    scene.spheres.push_back({{-0.2, 0.05, 0.1}, 0.08, 1});
    scene.planes.push_back({{0, -0.05, 0}, {0, 1, 0}, 1});
    SceneMeshes meshes;
    meshes.files = {share_mesh(bunny()), share_mesh(bunny())};
    for (int i = 0; i < 3; ++i) {
        Mesh block;
        block.translate = {0.25 * i - 0.25, 0, -0.1 * i};
        block.rotate_axis = {0, 1, 0};
        block.rotate_degrees = 40.0 * i;
        block.material = i % 2;
        scene.meshes.push_back(block);
        meshes.file_of_block.push_back(i == 0 ? 0 : 1);
    }
    const World world(scene, meshes);
    ASSERT_TRUE(world.top_level_linear());
    // Tiles only where the frame has kPixelsPerTriangle pixels for each triangle of the largest
    // mesh (the bunny's).
    size_t largest = 0;
    for (const MeshAccel& mesh : world.meshes()) largest = std::max(largest, mesh.triangle_count());
    ASSERT_GT(largest, 1000u);
    EXPECT_TRUE(world.frame_takes_tiles(World::kPixelsPerTriangle * largest));
    EXPECT_FALSE(world.frame_takes_tiles(World::kPixelsPerTriangle * largest - 1));
    int hits = 0, instance_hits = 0;
    for (const std::vector<Ray>& rays : packets(6000, 4)) {
        const int n = int(rays.size());
        const Ray* pointers[kPacket];
        for (int i = 0; i < n; ++i) pointers[i] = &rays[size_t(i)];
        std::optional<Hit> found[kPacket];
        SearchCounts counts;
        world.nearest_hits(pointers, n, {0, kInfinity}, found, counts);
        for (int i = 0; i < n; ++i) {
            const auto expected = world.nearest_hit(rays[size_t(i)], {0, kInfinity}, counts);
            ASSERT_EQ(found[i].has_value(), expected.has_value());
            if (!expected) continue;
            ++hits;
            instance_hits +=
                expected->object >= 3 && !world.instances()[world.objects()[expected->object].index].placed;
            ASSERT_EQ(found[i]->object, expected->object);
            ASSERT_EQ(found[i]->primitive, expected->primitive);
            ASSERT_EQ(found[i]->t, expected->t);
            ASSERT_EQ(found[i]->u, expected->u);
            ASSERT_EQ(found[i]->v, expected->v);
        }
    }
    EXPECT_GT(hits, 8000);
    EXPECT_GT(instance_hits, 1000);
}

}  // namespace
}  // namespace tracer
