// Shared by the hard cases of ../shared/spec/hard-cases.md (each case, its criterion and its
// figures: docs/robustness.md): a mesh behind its BVH and tested triangle by triangle, the
// three ways of aiming a ray, and the figures each case reports.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "accel/mesh_accel.h"
#include "accel/triangle.h"
#include "accel/world.h"
#include "io/obj_mesh.h"
#include "render/spawn.h"
#include "scene/scene.h"

namespace tracer::hard_cases {

// What a ray found in a mesh: the nearest triangle's t and outward face normal.
struct MeshResult {
    bool hit = false;
    Real t = 0;
    Vec3 face_normal{0};  // (v1 - v0) x (v2 - v0), normalised; zero for a zero-area triangle
    uint32_t triangle = 0;
};

// A mesh in its own coordinates, behind a SAH BVH and with every triangle tested.
class MeshUnderTest {
public:
    explicit MeshUnderTest(const TriangleMesh& mesh)
        : bvh_(mesh, Placement(), settings(false)), brute_(mesh, Placement(), settings(true)) {}

    MeshResult nearest(const Ray& ray) const { return query(bvh_, ray); }
    MeshResult nearest_brute(const Ray& ray) const { return query(brute_, ray); }
    const MeshAccel& bvh() const { return bvh_; }

private:
    static SearchSettings settings(bool brute_force) {
        SearchSettings s;
        s.brute_force = brute_force;
        s.threads = 1;
        return s;
    }
    static MeshResult query(const MeshAccel& accel, const Ray& ray) {
        Interval range{0, kInfinity};
        MeshHit hit;
        TraversalCounts counts;
        if (!accel.intersect(ray, range, hit, counts)) return {};
        return {true, hit.hit.t, accel.geometric_normal(hit.slot), accel.triangle_of(hit.slot)};
    }
    MeshAccel bvh_, brute_;
};

// The ways every aimed case is run (hard-cases.md, measurement conventions): the direction
// normalised in double and rounded to float, kept in double, and kept in double with one
// component moved one ulp up or down.
struct AimedRay {
    Ray ray;
    const char* way;
};
inline std::vector<AimedRay> aimed_rays(const Vec3& origin, const Vec3& target) {
    const Vec3 d = glm::normalize(target - origin);
    std::vector<AimedRay> out;
    out.push_back({{origin, Vec3(glm::vec3(d))}, "float-aimed"});
    out.push_back({{origin, d}, "double-aimed"});
    for (int k = 0; k < 3; ++k) {
        for (Real to : {kInfinity, -kInfinity}) {
            Vec3 moved = d;
            moved[k] = std::nextafter(d[k], to);
            out.push_back({{origin, moved}, "double-aimed, one component moved 1 ulp"});
        }
    }
    return out;
}

// A1's leak criterion for a closed shape in a world, tallied: rays aimed (every way) from a point
// inside at a point of its surface must meet it at the target's distance, to 10^-4 and `slack`
// (a few ulps of the coordinates): a later hit or none is a leak, a sooner one early.
struct AimedTally {
    int rays = 0, leaks = 0, early = 0, non_finite = 0;

    void aim(const World& world, const Vec3& inside, const Vec3& target, Real slack) {
        const Real distance = glm::length(target - inside);
        for (const AimedRay& aimed : aimed_rays(inside, target)) {
            ++rays;
            SearchCounts counts;
            const auto hit = world.nearest_hit(aimed.ray, kPrimaryRange, counts);
            leaks += !hit || hit->t > distance * (1 + 1e-4) + slack;
            early += hit && hit->t < distance * (1 - 1e-4) - slack;
            non_finite += hit && !std::isfinite(hit->t);
        }
    }
};

// A leak from inside a closed, outward-oriented mesh towards `target`: no hit, or a first hit
// that enters (n . d < 0) beyond the target (ties at the target are accepted).
inline bool interior_leak(const MeshResult& r, const Ray& ray, const Vec3& target) {
    if (!r.hit) return true;
    return glm::dot(r.face_normal, ray.direction) < 0 && r.t > glm::length(target - ray.origin) * (1 + 1e-4);
}

// True if any of t, the normal is NaN or infinite.
inline bool non_finite(const MeshResult& r) {
    return r.hit && !(std::isfinite(r.t) && std::isfinite(r.face_normal.x) && std::isfinite(r.face_normal.y) &&
                      std::isfinite(r.face_normal.z));
}

// ulp(x): the spacing of Real numbers at |x|.
inline Real ulp(Real x) {
    x = std::abs(x);
    return std::nextafter(x, kInfinity) - x;
}

// Records a figure for the report (tools/speed-vs-error reads them from --gtest_output=json)
// and prints it.
inline void report(const std::string& name, double value) {
    ::testing::Test::RecordProperty(name, std::to_string(value));
    std::printf("  %-40s %g\n", name.c_str(), value);
}

inline TriangleMesh load_obj(const std::string& relative) {
    Mesh block;
    block.path = (std::filesystem::path(TRACER_SOURCE_DIR) / relative).string();
    Diagnostics diagnostics;
    auto mesh = load_mesh(block, diagnostics);
    EXPECT_TRUE(mesh) << "cannot load " << relative;
    return mesh ? *mesh : TriangleMesh{};
}

// A scene with one material of the given kd and km, and nothing else yet.
inline SceneDescription empty_scene(double kd = 0.8, double km = 0) {
    SceneDescription scene;
    Material m;
    m.kd = dvec3(kd);
    m.km = dvec3(km);
    scene.materials.push_back(m);
    return scene;
}

// Uniform on the unit sphere.
inline Vec3 random_direction(std::mt19937& random) {
    std::normal_distribution<double> gauss;
    for (;;) {
        const Vec3 d(gauss(random), gauss(random), gauss(random));
        const Real length = glm::length(d);
        if (length > 1e-6) return d / length;
    }
}

}  // namespace tracer::hard_cases
