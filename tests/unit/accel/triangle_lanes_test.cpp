// The four-lane tests (accel/triangle_lanes.h), watertight and Moller-Trumbore, against the
// scalar ones they stand for: the same triangles hit, at the same t, u and v bit for bit.
#include <gtest/gtest.h>

#include <bit>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "accel/triangle_lanes.h"

namespace tracer {
namespace {

// Triangles in columns, as MeshAccel stores them (spare entries zero).
struct Columns {
    explicit Columns(const std::vector<Triangle>& triangles)
        : stride(triangles.size() + kTriangleLanes - 1), data(9 * stride, Real(0)) {
        for (size_t i = 0; i < triangles.size(); ++i) {
            const Vec3* v[3] = {&triangles[i].v0, &triangles[i].v1, &triangles[i].v2};
            for (int vertex = 0; vertex < 3; ++vertex)
                for (int axis = 0; axis < 3; ++axis) data[size_t(3 * vertex + axis) * stride + i] = (*v[vertex])[axis];
        }
    }
    TriangleColumns view() const { return {data.data(), stride}; }

    size_t stride;
    std::vector<Real> data;
};

// A grid of unit squares, two triangles each, sharing edges and vertices (rays through them
// test the watertight rules), then triangles of random size, place and shape, some with no area.
std::vector<Triangle> test_triangles(std::mt19937_64& random) {
    std::vector<Triangle> out;
    for (int y = -2; y < 2; ++y)
        for (int x = -2; x < 2; ++x) {
            const Vec3 a(x, y, 0), b(x + 1, y, 0), c(x + 1, y + 1, 0), d(x, y + 1, 0);
            out.push_back({a, b, c});
            out.push_back({a, c, d});
        }
    std::uniform_real_distribution<double> unit(-1, 1), exponent(-6, 6);
    for (int i = 0; i < 64; ++i) {
        const Real scale = Real(std::pow(10.0, exponent(random)));
        const Vec3 center = Vec3(unit(random), unit(random), unit(random)) * Real(3);
        auto corner = [&] { return center + scale * Vec3(unit(random), unit(random), unit(random)); };
        Triangle t{corner(), corner(), corner()};
        if (i % 8 == 0) t.v2 = t.v0 + (t.v1 - t.v0) * Real(0.5);  // collinear: no area
        if (i % 8 == 1) t.v1 = t.v0;                              // two corners the same
        out.push_back(t);
    }
    return out;
}

// Rays from random points towards the grid's vertices and edge midpoints, and towards random
// points near the triangles.
std::vector<Ray> test_rays(std::mt19937_64& random, const std::vector<Triangle>& triangles) {
    std::uniform_real_distribution<double> unit(-1, 1);
    std::uniform_int_distribution<size_t> pick(0, triangles.size() - 1);
    std::vector<Ray> out;
    for (int i = 0; i < 4000; ++i) {
        const Vec3 origin = Vec3(unit(random), unit(random), unit(random)) * Real(5);
        const Triangle& t = triangles[pick(random)];
        Vec3 target;
        switch (i % 4) {
            case 0: target = t.v0; break;
            case 1: target = (t.v0 + t.v1) * Real(0.5); break;
            case 2: target = (t.v0 + t.v1 + t.v2) / Real(3); break;
            default: target = Vec3(unit(random), unit(random), unit(random)) * Real(3);
        }
        if (target == origin) continue;
        out.push_back({origin, glm::normalize(target - origin)});
    }
    return out;
}

// The two hits' t, u and v are the same numbers, bit for bit.
void expect_same_hit(const TriangleHit& vector, const TriangleHit& scalar) {
    EXPECT_EQ(std::bit_cast<uint64_t>(double(vector.t)), std::bit_cast<uint64_t>(double(scalar.t)));
    EXPECT_EQ(std::bit_cast<uint64_t>(double(vector.u)), std::bit_cast<uint64_t>(double(scalar.u)));
    EXPECT_EQ(std::bit_cast<uint64_t>(double(vector.v)), std::bit_cast<uint64_t>(double(scalar.v)));
}

// Every lane of LaneTester (its candidates, then finish) answers as `scalar_test(lanes, ray,
// triangle, range, hit)` on random rays and triangles (seeded by `seed`), from every start, with
// every lane count and over three ranges: the same triangles hit, at the same t, u and v.
template <typename LaneTester, typename ScalarTest>
void expect_each_lane_answers_as(ScalarTest scalar_test, uint64_t seed) {
    std::mt19937_64 random(seed);
    const std::vector<Triangle> triangles = test_triangles(random);
    const Columns columns(triangles);
    const std::vector<Ray> rays = test_rays(random, triangles);
    const Interval ranges[] = {{0, kInfinity}, {Real(1e-3), Real(4)}, {Real(4), Real(9)}};
    int hits = 0, compared = 0;
    for (const Ray& ray : rays) {
        const LaneTester lanes(ray, columns.view());
        for (uint32_t first = 0; first < triangles.size(); ++first) {
            // Every start and every lane count: leaves begin anywhere and hold 1 to 4 here (the
            // lanes past them hold the next leaf's triangles, which must not count).
            const int most = int(std::min<size_t>(kTriangleLanes, triangles.size() - first));
            for (int count = 1; count <= most; ++count)
                for (const Interval& range : ranges) {
                    typename LaneTester::Candidate candidates[kTriangleLanes];
                    const unsigned mask = lanes.candidates(first, count, range, candidates);
                    ASSERT_EQ(mask >> count, 0u) << "a lane past the leaf's triangles";
                    for (int lane = 0; lane < count; ++lane) {
                        TriangleHit scalar, vector;
                        const bool scalar_hit = scalar_test(lanes, ray, triangles[first + lane], range, scalar);
                        const bool vector_hit =
                            (mask >> lane & 1) && LaneTester::finish(candidates, lane, range, vector);
                        ASSERT_EQ(vector_hit, scalar_hit) << "triangle " << first + lane;
                        ++compared;
                        if (!scalar_hit) continue;
                        ++hits;
                        expect_same_hit(vector, scalar);
                    }
                }
        }
    }
    EXPECT_GT(hits, compared / 200);  // not a test of misses alone
}

TEST(TriangleLanes, EachLaneAnswersAsTheScalarTestBitForBit) {
    expect_each_lane_answers_as<TriangleLaneTester>(
        [](const TriangleLaneTester& lanes, const Ray&, const Triangle& triangle, Interval range, TriangleHit& hit) {
            return intersect_triangle(lanes.shear, triangle, range, hit);
        },
        7);
}

TEST(TriangleLanes, MollerTrumboreLanesAnswerAsTheScalarTestBitForBit) {
    expect_each_lane_answers_as<MollerTrumboreLaneTester>(
        [](const MollerTrumboreLaneTester&, const Ray& ray, const Triangle& triangle, Interval range,
           TriangleHit& hit) { return intersect_triangle_moller_trumbore(ray, triangle, range, hit); },
        13);
}

TEST(TriangleLanes, CandidatesOfAWiderRangeFinishAsTheNarrowerRangesTest) {
    // A leaf's lanes are tested against the range it started with; a hit among them narrows
    // it, and the later lanes are checked against the narrower one (MeshAccel::intersect).
    std::mt19937_64 random(11);
    const std::vector<Triangle> triangles = test_triangles(random);
    const Columns columns(triangles);
    std::uniform_real_distribution<double> fraction(0, 1);
    int checked = 0;
    for (const Ray& ray : test_rays(random, triangles)) {
        const TriangleLaneTester lanes(ray, columns.view());
        for (uint32_t first = 0; first + kTriangleLanes <= triangles.size(); first += kTriangleLanes) {
            const Interval wide{0, kInfinity};
            ShearedTriangle sheared[kTriangleLanes];
            const unsigned mask = lanes.candidates(first, kTriangleLanes, wide, sheared);
            for (int lane = 0; lane < kTriangleLanes; ++lane) {
                TriangleHit wide_hit;
                if (!(mask >> lane & 1) || !finish_triangle_hit(sheared[lane], wide, wide_hit)) continue;
                // Ranges ending just before, at and just after the hit, and anywhere before it.
                const Real t = wide_hit.t;
                for (const Real end :
                     {std::nextafter(t, Real(0)), t, std::nextafter(t, kInfinity), Real(t * fraction(random))}) {
                    const Interval narrow{0, end};
                    TriangleHit scalar, vector;
                    const bool scalar_hit = intersect_triangle(lanes.shear, triangles[first + lane], narrow, scalar);
                    const bool vector_hit =
                        in_scaled_range(sheared[lane], narrow) && finish_triangle_hit(sheared[lane], narrow, vector);
                    ASSERT_EQ(vector_hit, scalar_hit);
                    ++checked;
                }
            }
        }
    }
    EXPECT_GT(checked, 1000);
}

}  // namespace
}  // namespace tracer
