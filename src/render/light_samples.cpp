#include "render/light_samples.h"

#include <cstring>

namespace tracer {
namespace {

constexpr uint64_t kGolden = 0x9E3779B97F4A7C15ull;

// splitmix64's finaliser (Steele, Lea and Flood 2014).
uint64_t mix(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

uint64_t bits(double value) {
    uint64_t out;
    std::memcpy(&out, &value, sizeof out);
    return out;
}

}  // namespace

uint64_t LightSamples::seed(const glm::dvec3& point, size_t light_index) {
    uint64_t h = mix(uint64_t(light_index) + kGolden);
    for (int c = 0; c < 3; ++c) h = mix((h ^ bits(point[c])) + kGolden);
    return h;
}

double LightSamples::draw(uint64_t seed, uint64_t k) {
    return double(mix(seed + (k + 1) * kGolden) >> 11) * 0x1p-53;
}

// The grid's places along an edge of n samples (Light::sample's k / (n - 1) - 1/2, 0 for one),
// worked out once per thread for each n.
static const double* grid_steps(int n) {
    thread_local std::vector<std::vector<double>> by_count;
    if (by_count.size() <= size_t(n)) by_count.resize(size_t(n) + 1);
    std::vector<double>& steps = by_count[size_t(n)];
    if (steps.empty()) {
        steps.resize(size_t(n));
        for (int k = 0; k < n; ++k) steps[size_t(k)] = n > 1 ? double(k) / (n - 1) - 0.5 : 0.0;
    }
    return steps.data();
}

LightSamples::LightSamples(const Light& light, size_t light_index, const Vec3& point) : light_(light) {
    const int n1 = light.samples1, n2 = light.samples2;
    grid1_ = grid_steps(n1), grid2_ = grid_steps(n2);
    if (!light.jitter) return;
    // Each thread's tables, kept between points (no allocation per point).
    thread_local std::vector<double> jitter1, jitter2;
    const uint64_t h = seed(glm::dvec3(point), light_index);
    jitter1.resize(size_t(n1) * size_t(n2));
    jitter2.resize(jitter1.size());
    for (int i = 0; i < n1; ++i)
        for (int j = 0; j < n2; ++j) {
            const size_t k = index(i, j);
            jitter1[k] = (i + draw(h, 2 * k)) / n1 - 0.5;
            jitter2[k] = (j + draw(h, 2 * k + 1)) / n2 - 0.5;
        }
    jitter1_ = jitter1.data(), jitter2_ = jitter2.data();
}

void LightSamples::hull(int i0, int i1, int j0, int j1, glm::dvec3 (&corners)[4]) const {
    if (!light_.jitter) {
        corners[0] = light_.sample(i0, j0), corners[1] = light_.sample(i1, j0);
        corners[2] = light_.sample(i1, j1), corners[3] = light_.sample(i0, j1);
        return;
    }
    const double a0 = double(i0) / light_.samples1 - 0.5, a1 = double(i1 + 1) / light_.samples1 - 0.5;
    const double b0 = double(j0) / light_.samples2 - 0.5, b1 = double(j1 + 1) / light_.samples2 - 0.5;
    const glm::dvec3 &c = light_.position, &e1 = light_.edge1, &e2 = light_.edge2;
    corners[0] = c + a0 * e1 + b0 * e2, corners[1] = c + a1 * e1 + b0 * e2;
    corners[2] = c + a1 * e1 + b1 * e2, corners[3] = c + a0 * e1 + b1 * e2;
}

}  // namespace tracer
