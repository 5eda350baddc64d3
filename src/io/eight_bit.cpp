#include "io/eight_bit.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace tracer {
namespace {

// The linear values at which to_8bit(srgb_encoded(v)) steps up: entry k is the least double v
// whose byte is k + 1 (found by bisection over the doubles, the curve being monotonic), so that
// 255 comparisons' worth of search give the byte the curve gives, without a pow per channel
// (which cost 4.5 ms of a 320 x 240 frame rendered in 12, measured).
const std::array<double, 255>& srgb_steps() {
    static const std::array<double, 255> steps = [] {
        std::array<double, 255> out{};
        for (int k = 0; k < 255; ++k) {
            double low = 0, high = 1;  // byte(low) <= k < k + 1 <= byte(high)
            while (std::nextafter(low, high) < high) {
                const double middle = low + (high - low) / 2;
                if (middle <= low || middle >= high) break;
                (to_8bit(srgb_encoded(middle)) > k ? high : low) = middle;
            }
            out[size_t(k)] = high;
        }
        return out;
    }();
    return steps;
}

// The steps cut 0..1 into cells of 1/kCells: each cell holds at most one step (the closest two,
// at the curve's foot, are 1 / (12.92 * 255) = 3.0e-4 apart), so a value's byte is its cell's
// first byte, plus one past the cell's step.
constexpr int kCells = 4096;
const std::array<unsigned char, kCells>& cell_bytes() {
    static const std::array<unsigned char, kCells> bytes = [] {
        std::array<unsigned char, kCells> out{};
        const auto& steps = srgb_steps();
        for (int cell = 0; cell < kCells; ++cell)
            out[size_t(cell)] = static_cast<unsigned char>(
                std::upper_bound(steps.begin(), steps.end(), double(cell) / kCells) - steps.begin());
        return out;
    }();
    return bytes;
}

// The byte of linear `value` by the sRGB curve: to_8bit(srgb_encoded(value)), by the steps.
unsigned char srgb_byte(double value) {
    if (!(value > 0)) return 0;
    if (value >= 1) return 255;
    const unsigned char first = cell_bytes()[size_t(value * kCells)];
    return first == 255 ? first : static_cast<unsigned char>(first + (value >= srgb_steps()[first]));
}

}  // namespace

bool srgb_bytes_match_the_curve(double value) {
    return srgb_byte(value) == to_8bit(srgb_encoded(value));
}

void eight_bit_rows(const Image& image, bool srgb, unsigned char* out) {
    if (srgb)
        std::transform(image.rgb.begin(), image.rgb.end(), out, srgb_byte);
    else
        std::transform(image.rgb.begin(), image.rgb.end(), out, to_8bit);
}

}  // namespace tracer
