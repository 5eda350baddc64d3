#include <gtest/gtest.h>

#include "lang/suggest.h"

namespace tracer {
namespace {

TEST(Suggest, EditDistanceCountsTranspositionsAsOneEdit) {
    EXPECT_EQ(edit_distance("radius", "radius"), 0);
    EXPECT_EQ(edit_distance("radus", "radius"), 1);
    EXPECT_EQ(edit_distance("centre", "center"), 1);
    EXPECT_EQ(edit_distance("Sphere", "sphere"), 0);
    EXPECT_EQ(edit_distance("", "abc"), 3);
}

TEST(Suggest, SuggestsOnlyLikelyTypos) {
    std::vector<std::string_view> keys{"center", "radius", "material"};
    EXPECT_EQ(closest_match("radus", keys), "radius");
    EXPECT_EQ(closest_match("centre", keys), "center");
    EXPECT_EQ(closest_match("matrial", keys), "material");
    EXPECT_EQ(closest_match("colour", keys), "");
    EXPECT_EQ(closest_match("x", {"n"}), "");
    EXPECT_EQ(did_you_mean("radus", keys), "; did you mean 'radius'?");
    EXPECT_EQ(did_you_mean("zzz", keys), "");
}

}  // namespace
}  // namespace tracer
