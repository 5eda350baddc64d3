// Each pattern's value at chosen points against its documented definition (scene/pattern.h,
// grammar/reference.md), worked out here by hand; colour maps, mappings, and image texels with
// their sRGB decoding, bilinear blend and wrap modes on tiny pictures.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "scene/noise.h"
#include "scene/pattern.h"

namespace tracer {
namespace {

using dvec3 = glm::dvec3;

Pattern map_pattern(PatternKind kind, std::vector<ColorStop> colors = {{0, dvec3(0)}, {1, dvec3(1)}}) {
    Pattern p;
    p.kind = kind;
    p.colors = std::move(colors);
    return p;
}

dvec3 color_at(const std::vector<Pattern>& patterns, const dvec3& point, const dvec3& uv = dvec3(0)) {
    return pattern_color(patterns, {}, 0, point, uv);
}

TEST(Pattern, CheckerAlternatesByTheSumOfFloors) {
    Pattern checker;
    checker.even = {dvec3(1, 0, 0)};
    checker.odd = {dvec3(0, 0, 1)};
    const std::vector<Pattern> patterns{checker};
    EXPECT_EQ(color_at(patterns, {0.5, 0.5, 0.5}), dvec3(1, 0, 0));   // 0 + 0 + 0
    EXPECT_EQ(color_at(patterns, {1.5, 0.5, 0.5}), dvec3(0, 0, 1));   // 1
    EXPECT_EQ(color_at(patterns, {1.5, 1.5, 0.5}), dvec3(1, 0, 0));   // 2
    EXPECT_EQ(color_at(patterns, {-0.5, 0.5, 0.5}), dvec3(0, 0, 1));  // -1
    EXPECT_EQ(color_at(patterns, {-0.5, -0.5, -0.5}), dvec3(0, 0, 1));
    // A floor at y = 0 whose points round just below it still takes the cell above.
    EXPECT_EQ(color_at(patterns, {0.5, -1e-12, 0.5}), dvec3(1, 0, 0));
    EXPECT_EQ(color_at(patterns, {0.5, 1e-12, 0.5}), dvec3(1, 0, 0));
    // Its own steps: scaled by 0.5 (to_pattern = x 2), cells are half as wide.
    std::vector<Pattern> small{checker};
    small[0].to_pattern.linear = glm::dmat3(2.0);
    EXPECT_EQ(color_at(small, {0.75, 0.25, 0.25}), dvec3(0, 0, 1));
}

TEST(Pattern, ScaledCopiesShareTheirUnscaledColour) {
    Pattern squares;
    squares.even = {dvec3(1, 0.85, 0.1)};
    squares.odd = {dvec3(0.9, 0.08, 0.05)};
    Pattern tenth = squares;  // `0.1 * squares`
    tenth.multiply = dvec3(0.1);
    Pattern moved = tenth;
    moved.to_pattern.offset = dvec3(0.5, 0, 0);
    Pattern recoloured = squares;
    recoloured.odd.color = dvec3(0);
    const std::vector<Pattern> patterns{squares, tenth, moved, recoloured};
    EXPECT_TRUE(same_but_multiply(patterns, 1, 0));
    EXPECT_TRUE(same_but_multiply(patterns, 0, 1));
    EXPECT_FALSE(same_but_multiply(patterns, 2, 0));  // placed elsewhere
    EXPECT_FALSE(same_but_multiply(patterns, 3, 0));  // another colour
    EXPECT_FALSE(same_but_multiply(patterns, -1, 0));
    const dvec3 point(1.5, 0.5, 0.5);
    EXPECT_EQ(pattern_color(patterns, {}, 1, point, dvec3(0)),
              dvec3(0.1) * unscaled_pattern_color(patterns, {}, 0, point, dvec3(0)));
    EXPECT_EQ(unscaled_pattern_color(patterns, {}, 1, point, dvec3(0)), dvec3(0.9, 0.08, 0.05));
}

TEST(Pattern, NestedCheckerIsEvaluatedInTheOuterSpace) {
    Pattern outer, inner;
    outer.even = {dvec3(0), 1};
    outer.odd = {dvec3(0.5)};
    outer.to_pattern.offset = dvec3(10, 0, 0);  // moved by -10 along x: cell parity unchanged
    inner.even = {dvec3(1, 1, 0)};
    inner.odd = {dvec3(0, 1, 1)};
    inner.to_pattern.linear = glm::dmat3(4.0);  // quarter-size cells inside
    const std::vector<Pattern> patterns{outer, inner};
    // (0.1, 0.1, 0.1): outer (10.1, 0.1, 0.1) even -> inner at 4 x that: floors 40 + 0 + 0, even.
    EXPECT_EQ(color_at(patterns, {0.1, 0.1, 0.1}), dvec3(1, 1, 0));
    // (0.3, 0.1, 0.1): outer even; inner (41.2, 0.4, 0.4): 41, odd.
    EXPECT_EQ(color_at(patterns, {0.3, 0.1, 0.1}), dvec3(0, 1, 1));
    EXPECT_EQ(color_at(patterns, {1.3, 0.1, 0.1}), dvec3(0.5));  // outer odd
}

TEST(Pattern, MultiplyScalesEveryColourNestedOnesTwice) {
    Pattern outer, inner;
    outer.even = {dvec3(0), 1};
    outer.odd = {dvec3(0.5)};
    outer.multiply = dvec3(0.5, 1, 2);
    inner.even = {dvec3(1)};
    inner.odd = {dvec3(1)};
    inner.multiply = dvec3(0.1);
    const std::vector<Pattern> patterns{outer, inner};
    const dvec3 even = color_at(patterns, {0.5, 0.5, 0.5});  // the inner checker, times both
    EXPECT_NEAR(even.r, 0.05, 1e-15);
    EXPECT_NEAR(even.g, 0.1, 1e-15);
    EXPECT_NEAR(even.b, 0.2, 1e-15);
    EXPECT_EQ(color_at(patterns, {1.5, 0.5, 0.5}), dvec3(0.25, 0.5, 1));
}

TEST(Pattern, ColorMapBlendsBetweenStopsAndHoldsBeyondThem) {
    const std::vector<ColorStop> stops{{0.2, dvec3(1, 0, 0)}, {0.6, dvec3(0, 0, 1)}, {0.6, dvec3(0, 1, 0)}};
    EXPECT_EQ(color_map_at(stops, 0.0), dvec3(1, 0, 0));
    EXPECT_EQ(color_map_at(stops, 0.2), dvec3(1, 0, 0));
    const dvec3 middle = color_map_at(stops, 0.4);
    EXPECT_NEAR(middle.r, 0.5, 1e-15);
    EXPECT_NEAR(middle.b, 0.5, 1e-15);
    EXPECT_EQ(color_map_at(stops, 0.6), dvec3(0, 1, 0));  // the later of two stops at one value
    EXPECT_EQ(color_map_at(stops, 0.9), dvec3(0, 1, 0));
    EXPECT_EQ(color_map_at(stops, 0.5, true), dvec3(1, 0, 0));  // stepped: the last at or below
    EXPECT_EQ(color_map_at(stops, 0.1, true), dvec3(1, 0, 0));  // below them all: the first
    EXPECT_EQ(color_map_at(stops, std::nan(""), false), dvec3(1, 0, 0));
    EXPECT_EQ(color_map_at({}, 0.5), dvec3(0));
}

TEST(Pattern, ValuesFollowTheirDefinitions) {
    const double kTurn = 2 * std::numbers::pi;
    Pattern gradient = map_pattern(PatternKind::Gradient);
    gradient.axis = glm::normalize(dvec3(1, 1, 0));
    const dvec3 q(0.3, 1.9, -4);
    const double along = (0.3 + 1.9) / std::sqrt(2.0);
    EXPECT_NEAR(pattern_value(gradient, q), along - std::floor(along), 1e-15);
    Pattern rings = map_pattern(PatternKind::Rings);           // around y
    EXPECT_NEAR(pattern_value(rings, {3, 7, 4}), 0.0, 1e-15);  // distance 5
    EXPECT_NEAR(pattern_value(rings, {0, 5, 2.25}), 0.25, 1e-15);
    Pattern spots = map_pattern(PatternKind::Spots);
    EXPECT_NEAR(pattern_value(spots, q), 0.5 + 0.5 * improved_noise(q), 1e-15);
    EXPECT_EQ(pattern_value(spots, {1, 2, 3}), 0.5);  // noise is 0 on the lattice
    Pattern marble = map_pattern(PatternKind::Marble);
    marble.axis = dvec3(1, 0, 0);
    marble.turbulence = 0.7;
    marble.octaves = 3;
    EXPECT_NEAR(pattern_value(marble, q), 0.5 + 0.5 * std::sin(kTurn * (0.3 + 0.7 * turbulence(q, 3))), 1e-15);
    Pattern wood = map_pattern(PatternKind::Wood);
    wood.turbulence = 0.1;
    wood.octaves = 2;
    const double w = std::sqrt(0.3 * 0.3 + 16) + 0.1 * turbulence(q, 2);
    EXPECT_NEAR(pattern_value(wood, q), w - std::floor(w), 1e-15);
    Pattern turb = map_pattern(PatternKind::Turbulence);
    turb.octaves = 5;
    EXPECT_NEAR(pattern_value(turb, q), std::min(1.0, turbulence(q, 5)), 1e-15);
    // Stripes: the map stepped; the default black/white halves.
    Pattern stripes = map_pattern(PatternKind::Stripes, {{0, dvec3(1)}, {0.5, dvec3(0)}});
    const std::vector<Pattern> striped{stripes};
    EXPECT_EQ(color_at(striped, {0, 0.49, 0}), dvec3(1));
    EXPECT_EQ(color_at(striped, {0, 0.51, 0}), dvec3(0));
    EXPECT_EQ(color_at(striped, {0, -0.25, 0}), dvec3(0));  // fraction 0.75
}

TEST(Pattern, MappingsFlattenThePoint) {
    EXPECT_EQ(mapped(Mapping::Planar, {1, 2, 3}), dvec3(1, 2, 0));
    const dvec3 front = mapped(Mapping::Spherical, {0, 0, 2});
    EXPECT_NEAR(front.x, 0.5, 1e-15);
    EXPECT_NEAR(front.y, 0.5, 1e-15);
    EXPECT_NEAR(mapped(Mapping::Spherical, {3, 0, 0}).x, 0.75, 1e-15);  // east of +z
    EXPECT_NEAR(mapped(Mapping::Spherical, {-3, 0, 0}).x, 0.25, 1e-15);
    EXPECT_NEAR(mapped(Mapping::Spherical, {0, 5, 0}).y, 1.0, 1e-15);  // the north pole
    EXPECT_NEAR(mapped(Mapping::Spherical, {0, -5, 0}).y, 0.0, 1e-15);
    EXPECT_NEAR(mapped(Mapping::Spherical, {1, 1, 0}).y, 0.75, 1e-15);  // 45 degrees north
    const dvec3 side = mapped(Mapping::Cylindrical, {-1, 7, 0});
    EXPECT_NEAR(side.x, 0.25, 1e-15);
    EXPECT_EQ(side.y, 7);
    EXPECT_EQ(mapped(Mapping::Spherical, dvec3(0)), dvec3(0.5, 0.5, 0));
}

TEST(Pattern, UvMappingReadsTheSurfaceCoordinatesNotThePoint) {
    Pattern checker;
    checker.mapping = Mapping::Uv;
    checker.to_pattern.linear = glm::dmat3(8.0);  // 8 x 8 squares over 0..1
    checker.even = {dvec3(1)};
    checker.odd = {dvec3(0)};
    const std::vector<Pattern> patterns{checker};
    EXPECT_EQ(color_at(patterns, {100, 100, 100}, {0.01, 0.01, 0}), dvec3(1));
    EXPECT_EQ(color_at(patterns, {100, 100, 100}, {0.13, 0.01, 0}), dvec3(0));
}

TEST(Image, SrgbBytesAreDecodedToLinear) {
    EXPECT_EQ(srgb_decoded(0), 0.0);
    EXPECT_EQ(srgb_decoded(255), 1.0);
    EXPECT_NEAR(srgb_decoded(10), 10 / 255.0 / 12.92, 1e-15);  // the linear segment
    EXPECT_NEAR(srgb_decoded(128), std::pow((128 / 255.0 + 0.055) / 1.055, 2.4), 1e-15);
    EXPECT_NEAR(srgb_decoded(188), 0.5029, 1e-4);  // the published mid-grey
}

// 2 x 2 grey float texels: top row 0, 1; bottom row 2, 3 (as in the file).
Texels two_by_two() {
    Texels t;
    t.width = 2, t.height = 2, t.channels = 1;
    t.floats = {0, 1, 2, 3};
    return t;
}

TEST(Image, TexelCentersAndBilinearBlend) {
    const Texels t = two_by_two();
    // Texel centers: u 0.25 and 0.75; v 0.75 is the top row, 0.25 the bottom.
    EXPECT_EQ(image_color(t, 0.25, 0.75, Wrap::Clamp), dvec3(0));
    EXPECT_EQ(image_color(t, 0.75, 0.75, Wrap::Clamp), dvec3(1));
    EXPECT_EQ(image_color(t, 0.25, 0.25, Wrap::Clamp), dvec3(2));
    EXPECT_EQ(image_color(t, 0.75, 0.25, Wrap::Clamp), dvec3(3));
    EXPECT_EQ(image_color(t, 0.5, 0.5, Wrap::Clamp), dvec3(1.5));
    EXPECT_EQ(image_color(t, 0.5, 0.75, Wrap::Clamp), dvec3(0.5));
}

TEST(Image, WrapModesOutsideTheSquare) {
    const Texels t = two_by_two();
    // Clamp: the edge texels go on.
    EXPECT_EQ(image_color(t, -3.0, 0.75, Wrap::Clamp), dvec3(0));
    EXPECT_EQ(image_color(t, 7.0, 0.25, Wrap::Clamp), dvec3(3));
    // Repeat: u = 1.25 is u = 0.25; between u = 0.75 and 1.25 the blend crosses the seam.
    EXPECT_EQ(image_color(t, 1.25, 0.75, Wrap::Repeat), dvec3(0));
    EXPECT_EQ(image_color(t, -0.75, 0.75, Wrap::Repeat), dvec3(0));
    EXPECT_EQ(image_color(t, 1.0, 0.75, Wrap::Repeat), dvec3(0.5));
    // Mirror: u = 1.25 is u = 0.75 (flipped), u = 2.25 is 0.25 again.
    EXPECT_EQ(image_color(t, 1.25, 0.75, Wrap::Mirror), dvec3(1));
    EXPECT_EQ(image_color(t, 2.25, 0.75, Wrap::Mirror), dvec3(0));
    EXPECT_EQ(image_color(t, -0.25, 0.75, Wrap::Mirror), dvec3(0));
    EXPECT_EQ(image_color(t, 1.0, 0.75, Wrap::Mirror), dvec3(1));
    // Far away and not finite: still a texel, no overflow.
    EXPECT_GE(image_color(t, 1e300, -1e300, Wrap::Repeat).r, 0.0);
    EXPECT_GE(image_color(t, std::nan(""), 0.5, Wrap::Mirror).r, 0.0);
    EXPECT_EQ(image_color(Texels{}, 0.5, 0.5, Wrap::Repeat), dvec3(0));
}

TEST(Image, EightBitRgbTexelsAreDecodedBeforeBlending) {
    Texels t;
    t.width = 2, t.height = 1, t.channels = 3;
    t.bytes = {0, 0, 0, 255, 128, 0};
    const dvec3 left = image_color(t, 0.25, 0.5, Wrap::Clamp);
    EXPECT_EQ(left, dvec3(0));
    const dvec3 between = image_color(t, 0.5, 0.5, Wrap::Clamp);
    EXPECT_NEAR(between.r, 0.5, 1e-15);  // the mean of the linear values, not of the bytes
    EXPECT_NEAR(between.g, srgb_decoded(128) / 2, 1e-15);
}

}  // namespace
}  // namespace tracer
