// SceneProgram: a scene compiled once gives, at every frame, exactly the scene that loading it
// afresh at that frame's clock gives (its state is reset between runs), and compiles once.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "lang/load_scene.h"
#include "lang/scene_program.h"
#include "scene/scene_json.h"

namespace tracer {
namespace {

std::string json_of(const LoadResult& result) {
    if (!result.scene) return "errors";
    std::ostringstream out;
    write_scene_json(out, *result.scene);
    return out.str();
}

std::string temporary_scene(const std::string& name, const std::string& text) {
    const std::filesystem::path path = std::filesystem::temp_directory_path() / name;
    std::ofstream(path) << text;
    return path.string();
}

FrameTime at(int frame, int count) {
    return {double(frame) / count, 1.0 / count, frame};
}

TEST(SceneProgram, EachFrameIsTheSceneLoadedAfreshAtItsClock) {
    // Loops, functions, groups, a parameter, the standard library, lets that close over the clock.
    const std::string path = temporary_scene("program_frames.scn", R"(
include "std/colors.scn"
param count = 3
let turn = 360 * clock
fn ring(n, r) {
  for i in 0..n { sphere { center (r * cos(turn + 360 * i / n), 0, r * sin(turn + 360 * i / n)) radius 0.2 + 0.1 * clock material { kd red } } }
}
camera { eye (0, 2, 6 + frame_number) lookat (0, 0, 0) }
light { position (3, 5, 4) color (1, 1, 1) * (1 - clock) }
group { rotate { axis (0, 1, 0) angle 10 * frame_number }
  ring(count + frame_number, 2)
  box { min (-1, -1, -1) max (1, 1, 1) * (1 + clock_delta) material { kd (clock, 0.5, 0.5) } }
}
)");
    for (const SceneArguments& arguments : {SceneArguments{}, SceneArguments{{{"count", "5"}}}}) {
        SceneProgram program(path, arguments);
        for (int frame = 0; frame < 4; ++frame) {
            SceneArguments fresh = arguments;
            fresh.frame = at(frame, 4);
            const LoadResult expected = load_scene(path, fresh);
            const LoadResult got = program.run(fresh.frame);
            ASSERT_TRUE(expected.scene) << frame;
            EXPECT_EQ(json_of(got), json_of(expected)) << "frame " << frame;
            EXPECT_EQ(got.scene->spheres.size(), expected.scene->spheres.size());
        }
        EXPECT_EQ(program.compilations(), 1);
    }
}

TEST(SceneProgram, FramesDifferWhereTheClockIsUsedAndAStillIsFrameZero) {
    const std::string path =
        temporary_scene("program_clock.scn",
                        "camera { eye (0, 0, 5) lookat (0, 0, 0) }\n"
                        "sphere { center (clock, frame_number, clock_delta) radius 1 material { kd 1 } }\n");
    SceneProgram program(path, {});
    const LoadResult first = program.run({});
    const LoadResult later = program.run({0.75, 0.25, 3});
    ASSERT_TRUE(first.scene && later.scene);
    EXPECT_EQ(first.scene->spheres[0].center, glm::dvec3(0, 0, 0));
    EXPECT_EQ(later.scene->spheres[0].center, glm::dvec3(0.75, 3, 0.25));
    EXPECT_EQ(json_of(load_scene(path)), json_of(first));  // a still image's clock is 0
}

TEST(SceneProgram, AnErrorAtOneFrameIsReportedThereAndTheNextFrameRunsClean) {
    const std::string path = temporary_scene("program_error.scn",
                                             "camera { eye (0, 0, 5) lookat (0, 0, 0) }\n"
                                             "sphere { center (0, 0, 0) radius 1 - frame_number material { kd 1 } }\n");
    SceneProgram program(path, {});
    EXPECT_TRUE(program.run({0, 0.5, 0}).scene);
    const LoadResult bad = program.run({0.5, 0.5, 1});  // radius 0
    EXPECT_FALSE(bad.scene);
    ASSERT_TRUE(bad.diagnostics.has_errors());
    EXPECT_EQ(bad.diagnostics.all().front().location.line, 2);
    EXPECT_FALSE(program.run({0.5, 0.5, 2}).scene);  // radius -1: an error again, not a crash
    EXPECT_EQ(program.compilations(), 1);
}

TEST(SceneProgram, ASceneThatFailsAtItsFirstRunFailsAfterwardsAndAMissingFileIsUnreadable) {
    const std::string path = temporary_scene("program_broken.scn", "sphere { radius }\n");
    SceneProgram program(path, {});
    EXPECT_FALSE(program.run({}).scene);
    EXPECT_FALSE(program.run({}).scene);
    SceneProgram missing("/nonexistent/scene.scn", {});
    const LoadResult result = missing.run({});
    EXPECT_TRUE(result.unreadable);
    EXPECT_FALSE(result.scene);
}

}  // namespace
}  // namespace tracer
