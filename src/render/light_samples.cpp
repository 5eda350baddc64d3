#include "render/light_samples.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

#include <glm/geometric.hpp>

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

// Multi-jittered sub-cells (Chiu, Shirley and Wang 1994): column i's samples take the sub-columns
// across1[i n2 + j], a shuffle of 0 .. n2-1, and row j's the sub-rows across2[j n1 + i], a shuffle
// of 0 .. n1-1; Fisher-Yates, t from n - 1 down to 1 swapping t with floor(draw (t + 1)), the
// draws from 2 n1 n2 on, columns first.
static void shuffle_sub_cells(uint64_t h, int n1, int n2, std::vector<int>& across1, std::vector<int>& across2) {
    uint64_t next = 2 * uint64_t(n1) * uint64_t(n2);
    const auto shuffle = [&](int* order, int n) {
        for (int t = 0; t < n; ++t) order[t] = t;
        for (int t = n - 1; t >= 1; --t) {
            const int r = std::min(t, int(LightSamples::draw(h, next++) * (t + 1)));
            std::swap(order[t], order[r]);
        }
    };
    across1.resize(size_t(n1) * size_t(n2));
    across2.resize(across1.size());
    for (int i = 0; i < n1; ++i) shuffle(&across1[size_t(i) * size_t(n2)], n2);
    for (int j = 0; j < n2; ++j) shuffle(&across2[size_t(j) * size_t(n1)], n1);
}

void LightSamples::concentric(double x, double y, double& u, double& v) {
    constexpr double kQuarterPi = 0.78539816339744830962;
    if (x == 0 && y == 0) {
        u = v = 0;
        return;
    }
    const bool wide = std::abs(x) > std::abs(y);
    const double r = wide ? x : y, angle = wide ? kQuarterPi * (y / x) : 2 * kQuarterPi - kQuarterPi * (x / y);
    u = r * std::cos(angle), v = r * std::sin(angle);
}

LightSamples::LightSamples(const Light& light, size_t light_index, const Vec3& point)
    : light_(light), edge1_(light.edge1), edge2_(light.edge2) {
    const int n1 = light.samples1, n2 = light.samples2;
    grid1_ = grid_steps(n1), grid2_ = grid_steps(n2);
    if (light.shape == Light::Shape::Sphere) {
        // The disc of the outline seen from the point: across the line to it, of the diameter.
        const glm::dvec3 away = glm::dvec3(point) - light.position;
        const double distance = glm::length(away);
        const glm::dvec3 w = distance > 0 ? away / distance : glm::dvec3(0, 0, 1);
        const glm::dvec3 helper = std::abs(w.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        const glm::dvec3 u = glm::normalize(glm::cross(helper, w));
        const double diameter = glm::length(light.edge1);
        edge1_ = diameter * u, edge2_ = diameter * glm::cross(w, u);
    }
    per_sample_ = light.jitter || light.shape != Light::Shape::Rectangle;
    if (!per_sample_) return;
    // Each thread's tables, kept between points (no allocation per point).
    thread_local std::vector<double> each1, each2;
    each1.resize(size_t(n1) * size_t(n2));
    each2.resize(each1.size());
    const uint64_t h = light.jitter ? seed(glm::dvec3(point), light_index) : 0;
    thread_local std::vector<int> across1, across2;  // each column's, each row's shuffled sub-cells
    if (light.jitter) shuffle_sub_cells(h, n1, n2, across1, across2);
    for (int i = 0; i < n1; ++i)
        for (int j = 0; j < n2; ++j) {
            const size_t k = index(i, j);
            double a = grid1_[size_t(i)], b = grid2_[size_t(j)];
            if (light.jitter) {
                const double u = draw(h, 2 * k), v = draw(h, 2 * k + 1);
                a = (i + (across1[k] + u) / n2) / n1 - 0.5;
                b = (j + (across2[size_t(j) * size_t(n1) + size_t(i)] + v) / n1) / n2 - 0.5;
            }
            if (light.shape != Light::Shape::Rectangle) {
                concentric(2 * a, 2 * b, a, b);
                a *= 0.5, b *= 0.5;
            }
            each1[k] = a, each2[k] = b;
        }
    each1_ = each1.data(), each2_ = each2.data();
}

void LightSamples::hull(int i0, int i1, int j0, int j1, glm::dvec3 (&corners)[4]) const {
    if (light_.shape != Light::Shape::Rectangle) {  // the square around the disc
        const glm::dvec3 &c = light_.position, h1 = 0.5 * edge1_, h2 = 0.5 * edge2_;
        corners[0] = c - h1 - h2, corners[1] = c + h1 - h2, corners[2] = c + h1 + h2, corners[3] = c - h1 + h2;
        return;
    }
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
