// Image regressions. scenes/task2.scn against the anchor pixels of conventions.md, the
// project's own golden image and (when ../shared is present) Figure 1 of the assignment;
// the bunny scenes against their golden images. TRACER_UPDATE_GOLDEN=1 rewrites the golden
// images (review the difference before committing).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <memory>

#include <OpenImageIO/imageio.h>
#include <glm/geometric.hpp>

#include "io/image_file.h"
#include "io/obj_mesh.h"
#include "lang/load_scene.h"
#include "render/renderer.h"
#include "scene/placement.h"

namespace tracer {
namespace {

namespace fs = std::filesystem;

struct Bytes {
    int width = 0, height = 0;
    std::vector<unsigned char> rgb;
    int at(int x, int y, int c) const { return rgb[(size_t(y) * width + x) * 3 + c]; }
};

Bytes to_bytes(const Image& image) {
    Bytes out{image.width, image.height, {}};
    for (double v : image.rgb) out.rgb.push_back(to_8bit(v));
    return out;
}

Bytes read_png(const fs::path& path) {
    auto input = OIIO::ImageInput::open(path.string());
    Bytes out;
    if (!input) return out;
    const OIIO::ImageSpec& spec = input->spec();
    out.width = spec.width;
    out.height = spec.height;
    out.rgb.resize(size_t(spec.width) * spec.height * 3);
    input->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, out.rgb.data());
    return out;
}

// Pixels where any channel differs by more than `levels`.
int pixels_differing(const Bytes& a, const Bytes& b, int levels) {
    int count = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            for (int c = 0; c < 3; ++c)
                if (std::abs(a.at(x, y, c) - b.at(x, y, c)) > levels) {
                    ++count;
                    break;
                }
    return count;
}

const fs::path kScenes = fs::path(TRACER_SOURCE_DIR) / "scenes";
const fs::path kGolden = fs::path(TRACER_SOURCE_DIR) / "tests" / "golden";

// Renders a scene file with its meshes, as `tracer` does (`size`: a square image of that many
// pixels a side instead of the scene's); writes the golden image on request.
Bytes render_scene(const std::string& name, const RenderOptions& options = {}, int size = 0) {
    LoadResult loaded = load_scene((kScenes / (name + ".scn")).string());
    EXPECT_TRUE(loaded.scene) << name;
    if (!loaded.scene) return {};
    if (size > 0) loaded.scene->render.width = loaded.scene->render.height = size;
    auto meshes = load_meshes(*loaded.scene, loaded.diagnostics);
    EXPECT_TRUE(meshes) << name;
    if (!meshes) return {};
    const World world(*loaded.scene, *meshes);
    Image image;
    RenderStats stats;
    EXPECT_TRUE(render(world, *loaded.scene, options, image, stats));
    if (std::getenv("TRACER_UPDATE_GOLDEN") && options.crop.width == 0)
        write_image((kGolden / (name + ".png")).string(), image);
    return to_bytes(image);
}

// Other compilers or CPUs (FMA) may move a few silhouette or shadow-edge pixels; nothing else
// may change: at most 0.01% of the pixels by more than one level.
void expect_matches_golden(const Bytes& rendered, const std::string& name) {
    Bytes golden = read_png(kGolden / (name + ".png"));
    ASSERT_EQ(golden.width, rendered.width) << "tests/golden/" << name << ".png missing or unreadable";
    ASSERT_EQ(golden.height, rendered.height);
    EXPECT_LE(pixels_differing(rendered, golden, 1), rendered.width * rendered.height / 10000);
}

class Task2 : public ::testing::Test {
protected:
    static void SetUpTestSuite() { rendered_ = std::make_unique<Bytes>(render_scene("task2")); }
    static std::unique_ptr<Bytes> rendered_;
};
std::unique_ptr<Bytes> Task2::rendered_;

TEST_F(Task2, AnchorPixelsOfConventionsWithinTwoLevels) {
    struct Anchor {
        int x, y, r, g, b;
    };
    const Anchor anchors[] = {
        {600, 80, 191, 191, 191},  {600, 250, 177, 177, 177}, {150, 300, 155, 155, 155}, {1150, 300, 120, 120, 120},
        {100, 700, 179, 179, 179}, {300, 720, 166, 166, 166}, {1100, 780, 91, 91, 91},   {1000, 650, 56, 56, 56},
        {360, 580, 31, 52, 31},    {850, 560, 26, 26, 54},    {450, 400, 29, 29, 29},    {720, 400, 23, 23, 23},
    };
    ASSERT_EQ(rendered_->width, 1200);
    ASSERT_EQ(rendered_->height, 800);
    for (const Anchor& a : anchors) {
        EXPECT_NEAR(rendered_->at(a.x, a.y, 0), a.r, 2) << "at (" << a.x << ", " << a.y << ")";
        EXPECT_NEAR(rendered_->at(a.x, a.y, 1), a.g, 2) << "at (" << a.x << ", " << a.y << ")";
        EXPECT_NEAR(rendered_->at(a.x, a.y, 2), a.b, 2) << "at (" << a.x << ", " << a.y << ")";
    }
}

TEST_F(Task2, MatchesTheCommittedGoldenImage) {
    expect_matches_golden(*rendered_, "task2");
}

TEST_F(Task2, MatchesFigure1OfTheAssignment) {
    fs::path figure = fs::path(SHARED_DIR) / "reference" / "figure1.png";
    if (!fs::exists(figure)) GTEST_SKIP() << "skipped: " << figure << " not present (needs ../shared)";
    Bytes reference = read_png(figure);
    ASSERT_EQ(reference.width, 1200);
    const int over_two_levels = pixels_differing(*rendered_, reference, 2);
    RecordProperty("pixels_over_2_levels", over_two_levels);
    std::cout << "[ figure 1 ] pixels differing by more than 2 levels: " << over_two_levels << " of 960000\n";
    EXPECT_LE(over_two_levels, 40);  // 19 since the first wave; hard-cases work may not cost more
}

TEST(Bunny, MatchesTheCommittedGoldenImage) {
    expect_matches_golden(render_scene("bunny"), "bunny");
}

TEST(BunnyRoom, MatchesTheCommittedGoldenImage) {
    expect_matches_golden(render_scene("bunny_room"), "bunny_room");
}

// The many-object scenes: 4,099 spheres through the top level's BVH; 64 instances of one mesh.
TEST(ManySpheres, MatchesTheCommittedGoldenImage) {
    expect_matches_golden(render_scene("many_spheres"), "many_spheres");
}

TEST(Bunnies, MatchesTheCommittedGoldenImage) {
    expect_matches_golden(render_scene("bunnies"), "bunnies");
}

// One OBJ cube shaded smooth and flat (`shading flat`).
TEST(Cubes, MatchesTheCommittedGoldenImage) {
    expect_matches_golden(render_scene("cubes"), "cubes");
}

// A room of quads and boxes only (finite flat shapes, transform steps, a mirrored triangle).
TEST(Room, MatchesTheCommittedGoldenImage) {
    expect_matches_golden(render_scene("room"), "room");
}

// A scene written with names, a parameter, expressions and loops (64 squares, 64 balls).
TEST(Chessboard, MatchesTheCommittedGoldenImage) {
    expect_matches_golden(render_scene("chessboard"), "chessboard");
}

// Refraction: two glass balls in task2's room (a regression guard; the rules themselves are
// checked by hand in refraction_test.cpp).
TEST(Glass, MatchesTheCommittedGoldenImage) {
    expect_matches_golden(render_scene("glass"), "glass");
}

// The seven SPD scenes as tools/nff2scn converts them (scenes/spd/), at 128 x 128: the
// importer's output, instancing of the cones, refraction in gears and mount.
class Spd : public ::testing::TestWithParam<const char*> {};

TEST_P(Spd, MatchesTheCommittedGoldenImage) {
    const std::string name = std::string("spd/") + GetParam();
    expect_matches_golden(render_scene(name, {}, 128), name);
}

INSTANTIATE_TEST_SUITE_P(Scenes, Spd, ::testing::Values("balls", "gears", "mount", "rings", "teapot", "tetra", "tree"));

TEST(BunnyRoom, BunnyStandsOnTheFloorClearOfEverySphere) {
    LoadResult loaded = load_scene((kScenes / "bunny_room.scn").string());
    ASSERT_TRUE(loaded.scene);
    auto meshes = load_meshes(*loaded.scene, loaded.diagnostics);
    ASSERT_TRUE(meshes && meshes->files.size() == 1);
    const Placement placement(loaded.scene->meshes[0]);
    double lowest = kInfinity;
    for (const auto& file_point : meshes->files[0]->positions) {
        const glm::dvec3 p = placement.point(file_point);
        lowest = std::min(lowest, p.y);
        for (const Sphere& s : loaded.scene->spheres)
            ASSERT_GT(glm::length(p - s.center), s.radius + 0.05) << "a bunny vertex is inside or touching a sphere";
    }
    EXPECT_GT(lowest, -1.0);    // above the floor plane y = -1 ...
    EXPECT_LT(lowest, -0.999);  // ... and standing on it
}

TEST(Crop, TheImageIsTheWindowWithEachPixelAsTheFullRenderHasIt) {
    RenderOptions options;
    options.crop = {500, 300, 120, 90};
    Bytes cropped = render_scene("task2", options);
    Bytes full = render_scene("task2");
    ASSERT_EQ(cropped.width, 120);
    ASSERT_EQ(cropped.height, 90);
    int differences = 0;
    for (int y = 0; y < cropped.height; ++y)
        for (int x = 0; x < cropped.width; ++x)
            for (int c = 0; c < 3; ++c) differences += cropped.at(x, y, c) != full.at(500 + x, 300 + y, c);
    EXPECT_EQ(differences, 0);
}

}  // namespace
}  // namespace tracer
