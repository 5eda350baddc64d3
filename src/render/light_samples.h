// Where an area light's samples lie, seen from one shaded point (docs/guide/lights.md): on the
// grid, corner to corner (Light::sample); or jittered, each at a random place in its cell of
// the rectangle and, along each edge alone, in a strip of its own (multi-jittered), the random
// numbers drawn from the point's coordinates and the light's index, so that an image is the
// same on any number of threads, tiles, regions or farm workers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "accel/types.h"
#include "scene/scene.h"

namespace tracer {

class LightSamples {
public:
    // `light_index`: the light's place in the scene's list; `point`: the point shaded. Its
    // tables are the calling thread's: one LightSamples at a time on a thread.
    LightSamples(const Light& light, size_t light_index, const Vec3& point);

    // Sample (i, j) (0 <= i < samples1 = N, 0 <= j < samples2 = M): centre + a edge1 + b edge2.
    // On the grid of a rectangle, Light::sample(i, j) bit for bit; jittered (Chiu, Shirley and
    // Wang's multi-jittering), a = (i + (s + u) / M) / N - 1/2, b = (j + (t + v) / N) / M - 1/2,
    // (u, v) sample k = i M + j's draws 2k and 2k + 1, s and t its sub-column and sub-row
    // (light_samples.cpp's shuffle_sub_cells: each column's a shuffle of 0 .. M-1, each row's of
    // 0 .. N-1, so that along each edge alone the N M samples fill the N M strips one each). On a
    // disc or a sphere, (a, b) mapped by concentric(2a, 2b) / 2 onto the inscribed disc; a sphere's
    // edges are those of the disc of its outline facing the point.
    glm::dvec3 position(int i, int j) const { return light_.position + along1(i, j) * edge1_ + along2(i, j) * edge2_; }
    // The a and b of sample (i, j).
    double along1(int i, int j) const { return per_sample_ ? each1_[index(i, j)] : grid1_[size_t(i)]; }
    double along2(int i, int j) const { return per_sample_ ? each2_[index(i, j)] : grid2_[size_t(j)]; }
    // The edges the samples lie along (a sphere's turned to face the point).
    const glm::dvec3& edge1() const { return edge1_; }
    const glm::dvec3& edge2() const { return edge2_; }
    // The corners, in order around it, of a quadrilateral holding samples [i0, i1] x [j0, j1]:
    // the four corner samples on a rectangle's grid, the cells' outer corners when jittered, the
    // square around the whole disc on a disc or a sphere.
    void hull(int i0, int i1, int j0, int j1, glm::dvec3 (&corners)[4]) const;
    // True if hull's corners are the corner samples themselves.
    bool corners_are_samples() const { return !light_.jitter && light_.shape == Light::Shape::Rectangle; }
    // True if a part of the grid has a smaller hull than the whole (not on a disc or a sphere).
    bool parts_have_hulls() const { return light_.shape == Light::Shape::Rectangle; }
    // Row i's a and b, one per j, into along1[0 .. samples2) and along2[0 .. samples2).
    template <typename T>
    void row(int i, T* along1, T* along2) const {
        const int n2 = light_.samples2;
        if (per_sample_) {
            for (int j = 0; j < n2; ++j) along1[j] = T(each1_[index(i, j)]), along2[j] = T(each2_[index(i, j)]);
        } else {
            for (int j = 0; j < n2; ++j) along1[j] = T(grid1_[size_t(i)]), along2[j] = T(grid2_[size_t(j)]);
        }
    }

    // Draw `k` (0, 1, 2, ...) of the generator seeded by (x, y, z, light_index), in [0, 1):
    // h = mix(light_index + G), then h = mix(h ^ bits(c) + G) for c = x, y, z as doubles;
    // draw k = (mix(h + (k + 1) G) >> 11) 2^-53; mix is splitmix64's finaliser, G = 0x9E3779B97F4A7C15.
    static uint64_t seed(const glm::dvec3& point, size_t light_index);
    static double draw(uint64_t seed, uint64_t k);
    // Shirley and Chiu's concentric map of the square [-1, 1]^2 onto the unit disc.
    static void concentric(double x, double y, double& u, double& v);

private:
    size_t index(int i, int j) const { return size_t(i) * size_t(light_.samples2) + size_t(j); }

    const Light& light_;
    glm::dvec3 edge1_, edge2_;
    bool per_sample_;      // a and b kept per sample (jittered, or on a disc or sphere)
    const double* grid1_;  // the grid's a for each i, b for each j
    const double* grid2_;
    const double* each1_ = nullptr;  // per sample: a and b
    const double* each2_ = nullptr;
};

}  // namespace tracer
