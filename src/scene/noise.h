// Ken Perlin's improved noise (SIGGRAPH 2002, "Improving Noise"), written from its published
// definition, and Perlin's turbulence (1985) built on it: the solid noise that patterns (marble,
// wood, turbulence) and the language's noise() and turbulence() share. The definition, exactly,
// so that an independent implementation reproduces every value (tests/cli/test_noise.py does):
//
// - P is Perlin's permutation of 0..255 (kPerlinPermutation below), read modulo 256.
// - fade(t) = t^3 (t (6 t - 15) + 10).
// - grad(h, x, y, z), with h = hash & 15: u = x if h < 8 else y; v = y if h < 4, else x if h is
//   12 or 14, else z; the result (u if h & 1 == 0 else -u) + (v if h & 2 == 0 else -v).
// - noise(x, y, z): X, Y, Z = floor of each, & 255; x, y, z -= their floors; u, v, w = fade of
//   each; A = P[X] + Y, AA = P[A] + Z, AB = P[A + 1] + Z, B = P[X + 1] + Y, BA = P[B] + Z,
//   BB = P[B + 1] + Z; then the trilinear blend by u, v, w (lerp(t, a, b) = a + t (b - a)) of
//   grad(P[AA], x, y, z), grad(P[BA], x-1, y, z), grad(P[AB], x, y-1, z), grad(P[BB], x-1, y-1, z)
//   and the same four with P[.. + 1] and z - 1: x blended first, then y, then z.
// - turbulence(p, octaves) = the sum over i = 0 .. octaves - 1 of |noise(2^i p)| / 2^i.
#pragma once

#include <array>
#include <cstdint>

#include <glm/vec3.hpp>

namespace tracer {

// Perlin's permutation of 0..255, as published with the reference implementation.
extern const std::array<uint8_t, 256> kPerlinPermutation;

// Improved noise at `p`: 0 at every point of the integer lattice, within about -1..1 elsewhere.
double improved_noise(const glm::dvec3& p);

// Most octaves a turbulence sums (beyond 30, 2^i p loses every bit of p's fraction).
constexpr int kMaxOctaves = 30;

// Perlin's turbulence: |noise| summed over `octaves` (1..kMaxOctaves), each twice the frequency
// and half the weight of the one before; 0 or more, below 2.
double turbulence(const glm::dvec3& p, int octaves);

}  // namespace tracer
