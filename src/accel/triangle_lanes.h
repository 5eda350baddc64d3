// The two triangle tests of triangle.h on four triangles at once, one per vector lane, for a BVH
// leaf's triangles stored coordinate by coordinate (TriangleColumns): the watertight test
// (TriangleLaneTester, the default rules) and Moller-Trumbore (MollerTrumboreLaneTester, the
// naive rules). Each lane does the very operations of the scalar test, so each gives the same
// answer bit for bit; the lanes that pass the tests' early steps are finished one by one, in
// order, by the scalar code.
#pragma once

#include <cstdint>
#include <cstring>

#if defined(__FMA__)
#include <immintrin.h>
#endif

#include "accel/triangle.h"

namespace tracer {

constexpr int kTriangleLanes = 4;
using RealLanes = Real __attribute__((vector_size(kTriangleLanes * sizeof(Real))));

// Every lane x.
inline RealLanes splat(Real x) {
    return RealLanes{x, x, x, x};
}

// a * b + c lane by lane, each rounded once (as std::fma).
template <typename Lanes>
inline Lanes fma_lanes(Lanes a, Lanes b, Lanes c) {
#if defined(__FMA__)
    if constexpr (sizeof(a[0]) == 8)
        return Lanes(_mm256_fmadd_pd(__m256d(a), __m256d(b), __m256d(c)));
    else
        return Lanes(_mm_fmadd_ps(__m128(a), __m128(b), __m128(c)));
#else
    Lanes out;
    for (int i = 0; i < kTriangleLanes; ++i) out[i] = std::fma(a[i], b[i], c[i]);
    return out;
#endif
}

// difference_of_products lane by lane.
inline RealLanes difference_of_products_lanes(RealLanes a, RealLanes b, RealLanes c, RealLanes d) {
    const RealLanes cd = c * d;
    const RealLanes error = fma_lanes(-c, d, cd);
    return fma_lanes(a, b, -cd) + error;
}

// Bit i set where lane i of a comparison's result is true.
template <typename Mask>
inline unsigned lanes_true(Mask m) {
    unsigned bits = 0;
    for (int i = 0; i < kTriangleLanes; ++i) bits |= unsigned(m[i] != 0) << i;
    return bits;
}

// Triangles stored as nine columns (vertex 0-2, axis x-z), each `stride` Reals long: the column
// of vertex v, axis k starts at base + (3 v + k) stride. Columns end with kTriangleLanes - 1
// spare entries, so that four lanes can be loaded from any triangle on.
struct TriangleColumns {
    const Real* base = nullptr;
    size_t stride = 0;

    const Real* column(int vertex, int axis) const { return base + size_t(3 * vertex + axis) * stride; }
    Triangle triangle(uint32_t i) const {
        auto vertex = [&](int v) { return Vec3(column(v, 0)[i], column(v, 1)[i], column(v, 2)[i]); };
        return {vertex(0), vertex(1), vertex(2)};
    }
};

// Steps 2 and 3 of intersect_triangle, lane by lane, on vertices translated, permuted and
// sheared (x, y; z not yet scaled by sz): bit i of the result is set where lane i passes them
// inside [range_min, range_max) (of the lanes in `lanes`), `sheared[i]` then holding what
// finish_triangle_hit needs. Each lane does the scalar test's very operations.
[[gnu::always_inline]] inline unsigned edge_and_range_steps(const RealLanes (&x)[3], const RealLanes (&y)[3],
                                                            RealLanes (&z)[3], RealLanes sz, RealLanes range_min,
                                                            RealLanes range_max, RealLanes error_scale, unsigned lanes,
                                                            ShearedTriangle (&sheared)[kTriangleLanes]) {
    // Step 2: the edge functions.
    const RealLanes e0 = difference_of_products_lanes(x[2], y[1], y[2], x[1]);
    const RealLanes e1 = difference_of_products_lanes(x[0], y[2], y[0], x[2]);
    const RealLanes e2 = difference_of_products_lanes(x[1], y[0], y[1], x[0]);
    const auto some_negative = (e0 < 0) | (e1 < 0) | (e2 < 0);
    const auto some_positive = (e0 > 0) | (e1 > 0) | (e2 > 0);
    const RealLanes det = e0 + e1 + e2;
    // Step 3: t times det against the range times det (in_scaled_range, lane by lane).
    for (int v = 0; v < 3; ++v) z[v] = z[v] * sz;
    const RealLanes t_scaled = fma_lanes(e0, z[0], fma_lanes(e1, z[1], e2 * z[2]));
    constexpr Real loose = kScaledRangeLoose;
    const RealLanes abs_det = det < 0 ? -det : det, t_signed = det < 0 ? -t_scaled : t_scaled;
    const auto in_range =
        (t_signed > range_min * abs_det * (1 - loose)) & (t_signed < range_max * abs_det * (1 + loose));
    const auto pass = ~(some_negative & some_positive) & (det != 0) & in_range;
    const unsigned mask = lanes_true(pass) & lanes;
    for (unsigned m = mask; m != 0; m &= m - 1) {
        const int i = __builtin_ctz(m);
        sheared[i] = {x[0][i], y[0][i], z[0][i], x[1][i], y[1][i], z[1][i],     x[2][i],       y[2][i],
                      z[2][i], e0[i],   e1[i],   e2[i],   det[i],  t_scaled[i], error_scale[i]};
    }
    return mask;
}

// What the four-lane test needs of a ray and a mesh, worked out once per ray: the shear, and the
// columns in the ray's frame (x, y, z = the shear's kx, ky, kz) for each vertex.
struct TriangleLaneTester {
    TriangleLaneTester(const Ray& ray, const TriangleColumns& columns) : shear(ray) {
        const int axes[3] = {shear.kx, shear.ky, shear.kz};
        for (int v = 0; v < 3; ++v)
            for (int k = 0; k < 3; ++k) rows[v][k] = columns.column(v, axes[k]);
    }

    // Steps 1-3 of intersect_triangle for triangles first .. first + 3, of which the first
    // `lanes` count: bit i of the result is set where triangle first + i passes them, and
    // `sheared` then holds what finish_triangle_hit needs of it (and in_scaled_range, to
    // check it again against a range that has shrunk since).
    unsigned candidates(uint32_t first, int lanes, Interval range, ShearedTriangle (&sheared)[kTriangleLanes]) const;

    // What candidates leaves of each lane that passes.
    using Candidate = ShearedTriangle;
    // The hit of candidate `lane`, if it is one inside `range` (which may have shrunk since).
    static bool finish(const ShearedTriangle (&sheared)[kTriangleLanes], int lane, Interval range, TriangleHit& hit) {
        return in_scaled_range(sheared[lane], range) && finish_triangle_hit(sheared[lane], range, hit);
    }

    RayShear shear;
    const Real* rows[3][3];  // [vertex][x, y, z in the ray's frame]
};

inline unsigned TriangleLaneTester::candidates(uint32_t first, int lanes, Interval range,
                                               ShearedTriangle (&sheared)[kTriangleLanes]) const {
    auto load = [&](int vertex, int axis) {
        RealLanes out;
        std::memcpy(&out, rows[vertex][axis] + first, sizeof out);
        return out;
    };
    // Step 1: translate, permute, shear.
    RealLanes x[3], y[3], z[3];
    for (int v = 0; v < 3; ++v) {
        z[v] = load(v, 2) - shear.origin.z;
        x[v] = fma_lanes(splat(-shear.sx), z[v], load(v, 0) - shear.origin.x);
        y[v] = fma_lanes(splat(-shear.sy), z[v], load(v, 1) - shear.origin.y);
    }
    return edge_and_range_steps(x, y, z, splat(shear.sz), splat(range.min), splat(range.max),
                                splat(shear.shear_error_scale), (1u << lanes) - 1, sheared);
}

// TriangleLaneTester turned sideways: one triangle against up to four rays, one per lane, for
// rays whose shears share their axes (kx, ky, kz: the same permutation of the columns). Each
// lane does the very operations of the scalar test on its ray, so each gives the same answer
// bit for bit. For a packet of rays that enter the same leaves (accel/ray_packet.h): a leaf
// holds fewer than four triangles on average, which left most of the other form's lanes idle.
struct RayLaneTester {
    // shears[0 .. count) (count at most kTriangleLanes) with the same axes; lanes past count copy
    // shears[0] (their answers are for the caller to ignore).
    RayLaneTester(const RayShear* const* shears, int count, const TriangleColumns& columns) {
        const int axes[3] = {shears[0]->kx, shears[0]->ky, shears[0]->kz};
        for (int v = 0; v < 3; ++v)
            for (int k = 0; k < 3; ++k) rows[v][k] = columns.column(v, axes[k]);
        for (int lane = 0; lane < kTriangleLanes; ++lane) {
            const RayShear& shear = *shears[lane < count ? lane : 0];
            origin_x[lane] = shear.origin.x, origin_y[lane] = shear.origin.y, origin_z[lane] = shear.origin.z;
            sx[lane] = shear.sx, sy[lane] = shear.sy, sz[lane] = shear.sz;
            error_scale[lane] = shear.shear_error_scale;
        }
    }

    // Steps 1-3 of intersect_triangle for triangle `triangle` against each lane's ray, inside
    // that lane's range [range_min, range_max): bit i of the result is set where ray i passes
    // them, `sheared[i]` then holding what finish_triangle_hit needs (TriangleLaneTester::finish).
    unsigned candidates(uint32_t triangle, RealLanes range_min, RealLanes range_max,
                        ShearedTriangle (&sheared)[kTriangleLanes]) const {
        // Step 1: translate, permute, shear.
        RealLanes x[3], y[3], z[3];
        for (int v = 0; v < 3; ++v) {
            z[v] = splat(rows[v][2][triangle]) - origin_z;
            x[v] = fma_lanes(-sx, z[v], splat(rows[v][0][triangle]) - origin_x);
            y[v] = fma_lanes(-sy, z[v], splat(rows[v][1][triangle]) - origin_y);
        }
        return edge_and_range_steps(x, y, z, sz, range_min, range_max, error_scale, (1u << kTriangleLanes) - 1,
                                    sheared);
    }

    RealLanes origin_x, origin_y, origin_z, sx, sy, sz, error_scale;
    const Real* rows[3][3];  // [vertex][x, y, z in the rays' frame]
};

// Moller-Trumbore (triangle.h) on four triangles at once, for the naive rules (TRACER_ROBUST=OFF):
// each lane does the very operations of intersect_triangle_moller_trumbore (one source,
// moller_trumbore_terms), so each gives the same answer bit for bit.
struct MollerTrumboreLaneTester {
    MollerTrumboreLaneTester(const Ray& ray, const TriangleColumns& columns) : triangles(columns) {
        for (int k = 0; k < 3; ++k) {
            origin[k] = splat(ray.origin[k]);
            direction[k] = splat(ray.direction[k]);
        }
    }

    // Bit i of the result is set where triangle first + i, of the first `lanes`, is hit inside
    // `range`; hits[i] is then its hit.
    [[gnu::always_inline]] unsigned candidates(uint32_t first, int lanes, Interval range,
                                               TriangleHit (&hits)[kTriangleLanes]) const {
        RealLanes v[3][3];
        for (int vertex = 0; vertex < 3; ++vertex)
            for (int axis = 0; axis < 3; ++axis)
                std::memcpy(&v[vertex][axis], triangles.column(vertex, axis) + first, sizeof(RealLanes));
        const auto fma = [](RealLanes a, RealLanes b, RealLanes c) { return fma_lanes(a, b, c); };
        const MollerTrumboreTerms<RealLanes> m = moller_trumbore_terms(origin, direction, v[0], v[1], v[2], fma);
        const unsigned mask = lanes_true(moller_trumbore_inside(m, range)) & ((1u << lanes) - 1);
        for (unsigned bits = mask; bits != 0; bits &= bits - 1) {
            const int i = __builtin_ctz(bits);
            hits[i] = {m.t[i], m.u[i], m.v[i]};
        }
        return mask;
    }

    using Candidate = TriangleHit;
    // Candidate `lane`'s hit, if still inside `range` (which may have shrunk since).
    static bool finish(const TriangleHit (&hits)[kTriangleLanes], int lane, Interval range, TriangleHit& hit) {
        if (!range.contains(hits[lane].t)) return false;
        hit = hits[lane];
        return true;
    }

    RealLanes origin[3], direction[3];
    TriangleColumns triangles;
};

}  // namespace tracer
