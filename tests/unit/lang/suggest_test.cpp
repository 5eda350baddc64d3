#include <gtest/gtest.h>

#include "lang/internal/suggest.h"

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

TEST(Suggest, OtherRenderersWordsSuggestOurs) {
    const std::vector<std::string_view> material{"ka", "kd", "ks", "km", "n", "kt", "ior"};
    EXPECT_EQ(closest_match("specular", material), "ks");
    EXPECT_EQ(closest_match("Diffuse", material), "kd");
    EXPECT_EQ(closest_match("ambient", material), "ka");
    EXPECT_EQ(closest_match("reflection", material), "km");
    EXPECT_EQ(closest_match("shininess", material), "n");
    EXPECT_EQ(closest_match("phong_size", material), "n");
    // The same word means the key the block has: eye in a camera, position in a light.
    EXPECT_EQ(closest_match("location", {"eye", "lookat", "up", "fovy", "focal"}), "eye");
    EXPECT_EQ(closest_match("location", {"position", "color"}), "position");
    EXPECT_EQ(closest_match("from", {"eye", "lookat", "up", "fovy", "focal"}), "eye");
    EXPECT_EQ(closest_match("pos", {"position", "color"}), "position");
    EXPECT_EQ(closest_match("point_light", {"camera", "render", "material", "sphere", "plane", "mesh", "light"}),
              "light");
    // A synonym without its key among the candidates suggests nothing.
    EXPECT_EQ(closest_match("specular", {"center", "radius", "material"}), "");
}

}  // namespace
}  // namespace tracer
