// The language as a program: expressions, names and their scopes, loops, parameters and
// includes, evaluated into the scene description (through load_scene_text, as tracer does).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>

#include "lang/load_scene.h"

namespace tracer {
namespace {

const std::string kCamera = "camera { eye (0, 0, 7) lookat (0, 0, 0) }\nlight { position (0, 5, 5) }\n";

LoadResult load(const std::string& text, const ParameterValues& parameters = {}, const InterpretLimits& limits = {}) {
    return load_scene_text("/scenes/t.scn", kCamera + text, false, parameters, limits);
}

std::vector<std::string> errors(const LoadResult& result) {
    std::vector<std::string> out;
    for (const Diagnostic& d : result.diagnostics.all())
        if (d.severity == Severity::Error) out.push_back(d.message);
    return out;
}

// The center of the only sphere of `expression` written as its center.
dvec3 center_of(const std::string& lets, const std::string& expression) {
    LoadResult r = load(lets + "\nsphere { center " + expression + " radius 1 material { kd 1 } }");
    EXPECT_TRUE(r.scene) << expression << ": " << (errors(r).empty() ? "" : errors(r)[0]);
    return r.scene ? r.scene->spheres.at(0).center : dvec3(-999);
}

double radius_of(const std::string& lets, const std::string& expression) {
    LoadResult r = load(lets + "\nsphere { center (0, 0, 0) radius " + expression + " material { kd 1 } }");
    EXPECT_TRUE(r.scene) << expression << ": " << (errors(r).empty() ? "" : errors(r)[0]);
    return r.scene ? r.scene->spheres.at(0).radius : -999;
}

TEST(Interpreter, ArithmeticFollowsTheUsualPrecedence) {
    EXPECT_EQ(radius_of("", "1 + 2 * 3"), 7);
    EXPECT_EQ(radius_of("", "(1 + 2) * 3"), 9);
    EXPECT_EQ(radius_of("", "8 / 4 / 2"), 1);  // left to right
    EXPECT_EQ(radius_of("", "2 - -1"), 3);
    EXPECT_EQ(radius_of("", "-2 * -1.5"), 3);
    EXPECT_EQ(radius_of("", "+4"), 4);
    EXPECT_EQ(radius_of("", "10 - 2 - 3"), 5);
    EXPECT_EQ(radius_of("let r = 0.25", "r * 4"), 1);
}

TEST(Interpreter, VectorsAddScaleAndHaveComponents) {
    EXPECT_EQ(center_of("let v = (1, 2, 3)", "v + (1, 1, 1)"), dvec3(2, 3, 4));
    EXPECT_EQ(center_of("let v = (1, 2, 3)", "2 * v - v / 2"), dvec3(1.5, 3, 4.5));
    EXPECT_EQ(center_of("let v = (1, 2, 3)", "(v.z, v.y * 2, -v.x)"), dvec3(3, 4, -1));
    EXPECT_EQ(center_of("let h = 0.5", "(0, h + 1, 0)"), dvec3(0, 1.5, 0));
    EXPECT_EQ(center_of("", "-(1, 2, 3)"), dvec3(-1, -2, -3));
}

TEST(Interpreter, FunctionsUseDegreesForAngles) {
    EXPECT_NEAR(radius_of("", "sin(30)"), 0.5, 1e-15);
    EXPECT_NEAR(radius_of("", "cos(60)"), 0.5, 1e-15);
    EXPECT_NEAR(radius_of("", "tan(45)"), 1, 1e-15);
    EXPECT_EQ(radius_of("", "sqrt(16)"), 4);
    EXPECT_EQ(radius_of("", "abs(-2)"), 2);
    EXPECT_EQ(radius_of("", "min(3, 2) + max(1, 0.5)"), 3);
    EXPECT_EQ(radius_of("", "floor(2.7)"), 2);
    EXPECT_EQ(radius_of("", "mod(7, 3) + mod(-1, 3)"), 3);  // mod takes the divisor's sign: 1 + 2
    EXPECT_EQ(radius_of("", "length((3, 4, 0))"), 5);
    EXPECT_EQ(radius_of("", "dot((1, 2, 3), (4, 5, 6))"), 32);
    EXPECT_EQ(radius_of("", "lerp(1, 3, 0.25)"), 1.5);
    EXPECT_EQ(center_of("", "cross((1, 0, 0), (0, 1, 0))"), dvec3(0, 0, 1));
    EXPECT_EQ(center_of("", "normalize((0, 3, 4))"), dvec3(0, 0.6, 0.8));
    EXPECT_EQ(center_of("", "lerp((0, 0, 0), (2, 4, 6), 0.5)"), dvec3(1, 2, 3));
    EXPECT_EQ(center_of("", "abs((-1, 2, -3))"), dvec3(1, 2, 3));
    EXPECT_NEAR(radius_of("", "pow(2, 3) + exp(0) + log(1)"), 9, 1e-15);
    EXPECT_NEAR(radius_of("", "asin(1) + acos(0) + atan(1) + atan2(1, 0)"), 315, 1e-12);
    EXPECT_NEAR(radius_of("", "1 + random(1, 2)"), 1.5, 0.5);
}

TEST(Interpreter, PiIsAConstantUnlessTheSceneNamesItOrAWordIsMeant) {
    EXPECT_EQ(radius_of("", "pi / 2"), std::numbers::pi / 2);
    EXPECT_EQ(radius_of("let pi = 3\n", "pi"), 3);  // the scene's own names come first
    // A key that takes a word (a material, a choice) reads `pi` as the word.
    LoadResult result = load("material pi { kd 1 }\nsphere { center (0, 0, 0) radius 1 material pi }");
    ASSERT_TRUE(result.scene) << errors(result)[0];
    EXPECT_EQ(result.scene->materials[result.scene->spheres[0].material].name, "pi");
}

TEST(Interpreter, LoopsRunFromTheFirstNumberUpToButNotIncludingTheEnd) {
    LoadResult r = load("for i in 0..4 { for j in i..3 { sphere { center (i, j, 0) radius 0.1 material { kd 1 } } } }");
    ASSERT_TRUE(r.scene) << errors(r)[0];
    // i = 0: j = 0, 1, 2; i = 1: j = 1, 2; i = 2: j = 2; i = 3: none.
    ASSERT_EQ(r.scene->spheres.size(), 6u);
    EXPECT_EQ(r.scene->spheres[0].center, dvec3(0, 0, 0));
    EXPECT_EQ(r.scene->spheres[3].center, dvec3(1, 1, 0));
    EXPECT_EQ(r.scene->spheres[5].center, dvec3(2, 2, 0));
    EXPECT_EQ(load("for i in 3..3 { sphere { center (0, 0, 0) radius 1 material { kd 1 } } }").scene->spheres.size(),
              0u);
    EXPECT_EQ(load("for i in -2..1 { sphere { center (i, 0, 0) radius 1 material { kd 1 } } }").scene->spheres.size(),
              3u);
}

TEST(Interpreter, LoopBodiesHaveTheirOwnScope) {
    // A name defined in a loop body shadows the file's and is gone after the loop; the loop's
    // own name too.
    LoadResult r = load(
        "let r = 1\n"
        "for i in 0..2 { let r = 0.25 * (i + 1) sphere { center (i, 0, 0) radius r material { kd 1 } } }\n"
        "sphere { center (5, 0, 0) radius r material { kd 1 } }\n");
    ASSERT_TRUE(r.scene) << errors(r)[0];
    EXPECT_EQ(r.scene->spheres[0].radius, 0.25);
    EXPECT_EQ(r.scene->spheres[1].radius, 0.5);
    EXPECT_EQ(r.scene->spheres[2].radius, 1);
    EXPECT_EQ(errors(load("for i in 0..2 { }\nsphere { center (i, 0, 0) radius 1 material { kd 1 } }")),
              std::vector<std::string>{"undefined name 'i'"});
    EXPECT_EQ(errors(load("let a = 1\nlet a = 2\n")), std::vector<std::string>{"'a' is already defined"});
}

TEST(Interpreter, WordsThatAreNotNamesReachTheValidator) {
    LoadResult r = load(
        "material gold { kd (1, 0.8, 0.2) }\nrender { accel median shadows false }\n"
        "sphere { center (0, 0, 0) radius 1 material gold }");
    ASSERT_TRUE(r.scene) << errors(r)[0];
    EXPECT_EQ(r.scene->render.accel, Accelerator::Median);
    EXPECT_FALSE(r.scene->render.shadows);
    // A word close to a defined name is taken for a misspelling of it.
    EXPECT_EQ(errors(load("let radius1 = 1\nsphere { center (0, 0, 0) radius radius2 material { kd 1 } }")),
              std::vector<std::string>{"undefined name 'radius2'; did you mean 'radius1'?"});
}

// `let gold = material { ... }` is a material value: the shapes using it share one material,
// equal to the named block's; a loop may pick one by value.
TEST(Interpreter, LetHoldsAMaterialThatShapesShare) {
    LoadResult a = load(
        "let gold = material { kd (1, 0.8, 0.2) ks 0.5 }\nsphere { center (0, 0, 0) radius 1 material gold }\n"
        "sphere { center (2, 0, 0) radius 1 material gold }");
    LoadResult b =
        load("material gold { kd (1, 0.8, 0.2) ks 0.5 }\nsphere { center (0, 0, 0) radius 1 material gold }");
    ASSERT_TRUE(a.scene && b.scene);
    ASSERT_EQ(a.scene->materials.size(), 1u);
    EXPECT_EQ(a.scene->spheres[1].material, 0);
    EXPECT_EQ(a.scene->materials[0].kd, b.scene->materials[0].kd);
    EXPECT_EQ(a.scene->materials[0].ks, b.scene->materials[0].ks);
    LoadResult picked = load(
        "let red = material { kd (1, 0, 0) }\nlet blue = material { kd (0, 0, 1) }\n"
        "for i in 0..4 {\n  let m = if mod(i, 2) == 0 { red } else { blue }\n"
        "  sphere { center (i, 0, 0) radius 0.4 material m }\n}");
    ASSERT_TRUE(picked.scene) << errors(picked)[0];
    ASSERT_EQ(picked.scene->materials.size(), 2u);
    EXPECT_EQ(picked.scene->materials[picked.scene->spheres[2].material].kd, dvec3(1, 0, 0));
    EXPECT_EQ(picked.scene->materials[picked.scene->spheres[3].material].kd, dvec3(0, 0, 1));
    EXPECT_EQ(
        errors(load("let t = transform { translate (1, 0, 0) }\nsphere { center (0, 0, 0) radius 1 material t }")),
        std::vector<std::string>{"'material' takes a material; this is a transform"});
}

TEST(Interpreter, ExpressionErrorsAreReportedWhereTheyHappen) {
    auto first_error = [](const std::string& text) {
        const auto found = errors(load(text));
        return found.empty() ? std::string("(none)") : found[0];
    };
    EXPECT_EQ(first_error("let a = 1 / (2 - 2)"), "division by zero");
    EXPECT_EQ(first_error("let a = 1e300 * 1e300"), "this expression's value is not finite (too large for a double)");
    EXPECT_EQ(first_error("let a = (1, 2, 3) * (1, 2, 3)"),
              "'*' does not multiply two vectors; use dot(a, b) or cross(a, b)");
    EXPECT_EQ(first_error("let a = (1, 2, 3) + 1"),
              "'+' needs two numbers or two vectors; this is a number and a vector");
    EXPECT_EQ(first_error("let a = sqrt(-1)"), "sqrt of a negative number (-1)");
    EXPECT_EQ(first_error("let a = sqr(4)"), "unknown function 'sqr'; did you mean 'sqrt'?");
    EXPECT_EQ(first_error("let a = min(1)"), "'min' takes 2 arguments, found 1");
    EXPECT_EQ(first_error("let a = (1, 2, 3).w"), "a vector's components are x, y and z; found 'w'");
    EXPECT_EQ(first_error("let a = 2.x"), "malformed number '2.x'");  // the lexer's, once
    EXPECT_EQ(first_error("for i in 0..2.5 { }"), "a range goes from whole number to whole number; this is 2.5");
    EXPECT_EQ(first_error("let a = \"text\"\nsphere { center (0, 0, 0) radius a material { kd 1 } }"),
              "'radius' expects a number, found a string");
    EXPECT_EQ(first_error("sphere { center (0, 0, 0) radius = 1 material { kd 1 } }"),
              "a key takes its value without '=': write 'radius value'");
}

TEST(Interpreter, ErrorsInALoopNameTheIteration) {
    LoadResult r = load("for i in 0..3 { sphere { center (0, 0, 0) radius 1 - i material { kd 1 } } }");
    ASSERT_FALSE(r.scene);
    ASSERT_EQ(errors(r).size(), 1u);  // i = 1, with i = 2 counted as a repeat
    const Diagnostic& first = r.diagnostics.all().back();
    EXPECT_EQ(first.message, "'radius' must be greater than 0, found 0");
    ASSERT_EQ(first.notes.size(), 1u);
    EXPECT_EQ(first.notes[0].message, "in iteration i = 1 of this loop");
    EXPECT_EQ(first.notes[0].location.column, 1);
    EXPECT_EQ(first.repeats, 1);
}

TEST(Interpreter, ParametersTakeTheirValueFromTheCommandLine) {
    const std::string text =
        "param r = 0.5\nparam colour = (1, 1, 1)\n"
        "sphere { center (0, 0, 0) radius r material { kd colour } }";
    LoadResult defaults = load(text);
    ASSERT_TRUE(defaults.scene);
    EXPECT_EQ(defaults.scene->spheres[0].radius, 0.5);
    LoadResult set = load(text, {{"r", "0.25 * 2 + 1"}, {"colour", "(1, 0, 0)"}});
    ASSERT_TRUE(set.scene) << errors(set)[0];
    EXPECT_EQ(set.scene->spheres[0].radius, 1.5);
    EXPECT_EQ(set.scene->materials.back().kd, dvec3(1, 0, 0));
    EXPECT_EQ(errors(load(text, {{"colur", "2"}})),
              std::vector<std::string>{"-D colur: the scene has no 'param colur'; did you mean 'colour'?"});
    EXPECT_EQ(errors(load("for i in 0..2 { param p = 1 }")),
              std::vector<std::string>{"a 'param' is declared at the top level of a file, not inside braces"});
}

TEST(Interpreter, AnErrorRepeatedByALoopIsOnePlaceCountedOnce) {
    // 25 mistakes, each in all 100 iterations: 25 errors kept, each with 99 repeats; the limit
    // of errors shown counts the 25 places.
    std::string body;
    for (int k = 0; k < 25; ++k)
        body += "sphere { center (i, " + std::to_string(k) + ", 0) radius 0 material { kd 1 } }\n";
    LoadResult result = load("for i in 0..100 {\n" + body + "}");
    EXPECT_EQ(result.diagnostics.error_count(), 25);
    for (const Diagnostic& d : result.diagnostics.all()) {
        EXPECT_EQ(d.repeats, 99) << d.message;
        EXPECT_EQ(d.repeated_in, Diagnostic::RepeatedIn::Iterations);
    }
}

TEST(Interpreter, LimitsStopRunawayScenes) {
    InterpretLimits limits;
    limits.max_blocks = 100;
    limits.max_iterations = 1000;
    EXPECT_EQ(errors(load("for i in 0..1000 { sphere { center (0, 0, 0) radius 1 material { kd 1 } } }", {}, limits)),
              std::vector<std::string>{"the scene generates more than 100 blocks (the limit); generate fewer"});
    EXPECT_EQ(errors(load("for i in 0..100 { for j in 0..100 { } }", {}, limits)),
              std::vector<std::string>{"the scene runs more than 1000 loop iterations (the limit)"});
}

// The work limit counts operations, not statements: 20 iterations of one statement of 1,000
// terms (over 1,000 operations each) pass 10,000 operations where 100 short statements do not.
TEST(Interpreter, TheWorkLimitCountsOperationsNotStatements) {
    InterpretLimits limits;
    limits.max_operations = 10'000;
    std::string sum = "i";
    for (int k = 1; k < 1000; ++k) sum += " + i";
    const std::vector<std::string> stopped = errors(load("for i in 0..20 { let t = " + sum + " }", {}, limits));
    ASSERT_EQ(stopped.size(), 1u);
    EXPECT_EQ(stopped[0].rfind("the scene runs more than 10000 operations (the limit: each statement run and each "
                               "operation of an expression counts one)",
                               0),
              0u)
        << stopped[0];
    EXPECT_TRUE(errors(load("for i in 0..100 { let t = i + 1 }", {}, limits)).empty());
}

class Includes : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() /
               ("tracer_include_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::create_directories(dir_ / "lib");
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    void write(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }
    LoadResult load_file(const std::string& name) { return load_scene((dir_ / name).string()); }
    std::filesystem::path dir_;
};

TEST_F(Includes, AnIncludedFilesBlocksAndNamesComeInPlace) {
    write("lib/materials.scn", "material gold { kd (1, 0.8, 0.2) }\nlet size = 0.5\n");
    write("main.scn", kCamera + "include \"lib/materials.scn\"\nsphere { center (0, 0, 0) radius size material gold }");
    LoadResult r = load_file("main.scn");
    ASSERT_TRUE(r.scene) << errors(r)[0];
    EXPECT_EQ(r.scene->spheres[0].radius, 0.5);
    EXPECT_EQ(r.scene->materials[0].name, "gold");
}

// A file included by a loop runs in each iteration, seeing the loop's names; its text is read and
// held once.
TEST_F(Includes, AFileIncludedByALoopRunsEachTime) {
    write("lib/ball.scn", "sphere { center (i, 0, 0) radius 0.25 material { kd 1 } }\n");
    write("main.scn", kCamera + "for i in 0..3 { include \"lib/ball.scn\" }\n");
    LoadResult r = load_file("main.scn");
    ASSERT_TRUE(r.scene) << errors(r)[0];
    ASSERT_EQ(r.scene->spheres.size(), 3u);
    EXPECT_EQ(r.scene->spheres[2].center, dvec3(2, 0, 0));
}

TEST_F(Includes, ErrorsPointIntoTheIncludedFileAndSayFromWhere) {
    write("lib/bad.scn", "sphere { center (0, 0, 0) radius -1 material { kd 1 } }\n");
    write("main.scn", kCamera + "include \"lib/bad.scn\"\n");
    LoadResult r = load_file("main.scn");
    ASSERT_EQ(errors(r).size(), 1u);
    const Diagnostic& d = r.diagnostics.all()[0];
    EXPECT_EQ(d.location.path, (dir_ / "lib/bad.scn").string());
    ASSERT_EQ(d.notes.size(), 1u);
    EXPECT_EQ(d.notes[0].message, "included from here");
    EXPECT_EQ(d.notes[0].location.path, (dir_ / "main.scn").string());
    EXPECT_EQ(d.notes[0].location.line, 3);
}

TEST_F(Includes, CyclesAndMissingFilesAreErrors) {
    write("a.scn", "include \"b.scn\"\n");
    write("b.scn", "include \"a.scn\"\n");
    write("main.scn", kCamera + "include \"a.scn\"\ninclude \"missing.scn\"\n");
    const auto found = errors(load_file("main.scn"));
    ASSERT_EQ(found.size(), 2u);
    EXPECT_EQ(found[0], "'a.scn' includes itself (through the files noted)");
    EXPECT_NE(found[1].find("cannot include"), std::string::npos);
}

// A scene that includes itself is caught at that include, before its blocks run again (they
// would first be reported as a second render and camera block).
TEST_F(Includes, ASceneIncludingItselfIsOneErrorAtTheInclude) {
    write("self.scn", "render { width 10 height 10 }\n" + kCamera + "include \"self.scn\"\n");
    EXPECT_EQ(errors(load_file("self.scn")),
              std::vector<std::string>{"'self.scn' includes itself (through the files noted)"});
}

// 32 files may be included one inside another below the scene; the 33rd is refused.
TEST_F(Includes, ThirtyTwoNestedIncludesAreTheLimit) {
    for (int depth : {32, 33}) {
        for (int i = 1; i <= depth; ++i)
            write("n" + std::to_string(i) + ".scn",
                  i < depth ? "include \"n" + std::to_string(i + 1) + ".scn\"\n" : "");
        write("main.scn", kCamera + "include \"n1.scn\"\n");
        const auto found = errors(load_file("main.scn"));
        if (depth == 32)
            EXPECT_TRUE(found.empty()) << found[0];
        else
            EXPECT_EQ(found, std::vector<std::string>{"includes are nested too deeply (more than 32 files)"});
    }
}

TEST_F(Includes, MeshPathsAreRelativeToTheFileTheyAreWrittenIn) {
    write("lib/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    write("lib/mesh.scn", "mesh { file \"tri.obj\" material { kd 1 } }\n");
    write("main.scn", kCamera + "include \"lib/mesh.scn\"\n");
    LoadResult r = load_file("main.scn");
    ASSERT_TRUE(r.scene) << errors(r)[0];
    EXPECT_EQ(r.scene->meshes[0].path, (dir_ / "lib/tri.obj").lexically_normal().string());
}

}  // namespace
}  // namespace tracer
