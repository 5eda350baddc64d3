// The sRGB bytes of tracer's own PNG and PPM writer: a table of the curve's steps gives exactly the
// byte of the curve itself, to_8bit(srgb_encoded(v)), at and around every step and at random values.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "base/image.h"
#include "io/native_images.h"

namespace tracer {
namespace {

TEST(NativeImages, SrgbBytesAreTheCurvesAtEveryStepAndBetween) {
    // Around each byte's step: the least value of each byte found by bisection here, then its
    // neighbours one double away on each side.
    for (int k = 1; k <= 255; ++k) {
        double low = 0, high = 1;
        for (int i = 0; i < 200; ++i) {
            const double middle = (low + high) / 2;
            (to_8bit(srgb_encoded(middle)) >= k ? high : low) = middle;
        }
        for (double v = std::nextafter(high, 0.0), n = 0; n < 3; v = std::nextafter(v, 2.0), ++n)
            EXPECT_TRUE(srgb_bytes_match_the_curve(v)) << "byte " << k << " at " << v;
    }
    std::mt19937_64 random(57);
    std::uniform_real_distribution<double> unit(0, 1), wide(-0.5, 2);
    for (int i = 0; i < 1'000'000; ++i) {
        const double v = i % 2 ? unit(random) : wide(random);
        ASSERT_TRUE(srgb_bytes_match_the_curve(v)) << v;
    }
    for (double v : {0.0, -0.0, 1.0, 1e-300, 0.0031308, std::nan(""), 1e300})
        EXPECT_TRUE(srgb_bytes_match_the_curve(v)) << v;
}

}  // namespace
}  // namespace tracer
