// The language's third wave: functions (scope, recursion, closures, the depth limit), booleans
// and conditions, lists, values of every kind, and groups composing placements, evaluated into
// the scene description through load_scene_text as tracer does.
#include <gtest/gtest.h>

#include <cmath>

#include "lang/load_scene.h"
#include "scene/placement.h"

namespace tracer {
namespace {

const std::string kCamera = "camera { eye (0, 0, 7) lookat (0, 0, 0) }\nlight { position (0, 5, 5) }\n";

LoadResult load(const std::string& text) {
    return load_scene_text("/scenes/t.scn", kCamera + text, false, {}, {});
}

std::vector<std::string> errors(const LoadResult& result) {
    std::vector<std::string> out;
    for (const Diagnostic& d : result.diagnostics.all())
        if (d.severity == Severity::Error) out.push_back(d.message);
    return out;
}

std::string first_error(const std::string& text) {
    const auto found = errors(load(text));
    return found.empty() ? std::string("(none)") : found[0];
}

// The radius of the only sphere, whose radius is `expression` after `lets`.
double radius_of(const std::string& lets, const std::string& expression) {
    LoadResult r = load(lets + "\nsphere { center (0, 0, 0) radius " + expression + " material { kd 1 } }");
    EXPECT_TRUE(r.scene) << expression << ": " << (errors(r).empty() ? "" : errors(r)[0]);
    return r.scene && !r.scene->spheres.empty() ? r.scene->spheres[0].radius : -999;
}

TEST(Language, FunctionsReturnValuesWithLexicalScope) {
    EXPECT_EQ(radius_of("fn twice(x) { return 2 * x }", "twice(0.25)"), 0.5);
    // The body sees the names defined before the function, not the caller's.
    EXPECT_EQ(radius_of("let k = 3\nfn f(x) { return k * x }\nlet g = 10", "f(0.5)"), 1.5);
    EXPECT_EQ(first_error("fn f(x) { return x * caller }\nlet caller = 2\nlet y = f(1)"), "undefined name 'caller'");
    // Parameters hide outer names; a function's names end with its body.
    EXPECT_EQ(radius_of("let x = 100\nfn f(x) { let y = x + 1\n return y }", "f(1)"), 2);
    EXPECT_EQ(first_error("fn f(x) { let y = x\n return y }\nlet z = y"), "undefined name 'y'");
}

TEST(Language, RecursionRunsAndIsBoundedWithTheCallChain) {
    EXPECT_EQ(radius_of("fn fact(n) { if n <= 1 { return 1 }\n return n * fact(n - 1) }", "fact(5) / 100"), 1.2);
    EXPECT_EQ(radius_of("fn depth(n) { return if n == 0 { 0 } else { 1 + depth(n - 1) } }", "depth(9999) / 9999"), 1);
    LoadResult deep = load("fn down(n) { return down(n + 1) }\nlet x = down(0)");
    ASSERT_FALSE(errors(deep).empty());
    EXPECT_EQ(errors(deep)[0], "calls nest more than 10000 deep (the limit): a recursion that does not stop?");
    const Diagnostic& d = deep.diagnostics.all()[0];
    ASSERT_EQ(d.notes.size(), 3u);  // a recursion: the innermost call, one line for the rest, the outermost
    EXPECT_EQ(d.notes[0].message, "in this call of 'down'");
    EXPECT_EQ(d.notes[1].message, "... and 9998 more levels of calls and loops: calls of 'down' ...");
    EXPECT_EQ(d.notes[1].location.line, 0);  // one line, without the source
    EXPECT_EQ(d.notes[2].location.line, 4);  // the first call, at the top of the file
}

TEST(Language, FunctionsCloseOverTheValuesAroundTheirDefinition) {
    // Made in a loop, each function keeps its own iteration's value.
    LoadResult r = load(
        "let fs = [0, 1, 2]\nfor i in 0..3 {\n  fn scaled(x) { return x * (i + 1) }\n"
        "  sphere { center (i, 0, 0) radius scaled(0.25) material { kd 1 } }\n}");
    ASSERT_TRUE(r.scene) << errors(r)[0];
    ASSERT_EQ(r.scene->spheres.size(), 3u);
    EXPECT_EQ(r.scene->spheres[2].radius, 0.75);
    // A function defined in a function, using the outer one's parameter.
    EXPECT_EQ(radius_of("fn outer(a) {\n fn inner(b) { return a + b }\n return inner(0.5) }", "outer(1)"), 1.5);
}

TEST(Language, CallsForBlocksAndForValuesAreKeptApart) {
    LoadResult r = load(
        "fn flake(c, r, depth) {\n  sphere { center c radius r material { kd 1 } }\n"
        "  if depth > 0 {\n    for k in 0..3 { flake(c + (r * 1.5 * cos(120 * k), r * 1.5 * sin(120 * k), 0), "
        "r / 3, depth - 1) }\n  }\n}\nflake((0, 0, 0), 1, 2)");
    ASSERT_TRUE(r.scene) << errors(r)[0];
    EXPECT_EQ(r.scene->spheres.size(), 1u + 3u + 9u);
    EXPECT_EQ(r.scene->spheres[1].radius, 1.0 / 3);
    EXPECT_EQ(first_error("fn s() { sphere { center (0, 0, 0) radius 1 material { kd 1 } } }\nlet x = s()"),
              "a function called for its value makes no blocks: call 's(...)' alone, as a statement, for its blocks");
    EXPECT_EQ(first_error("fn f() { return 1 }\nf()"),
              "'f' gives a value, which a statement leaves unused; keep it with 'let NAME = f(...)'");
    EXPECT_EQ(first_error("fn f(x) { if x > 0 { return 1 } }\nlet y = f(-1)"),
              "'f' gives no value here: its body ends without 'return VALUE'");
    EXPECT_EQ(first_error("fn f(a, b) { return a }\nlet y = f(1)"), "'f' takes 2 arguments, found 1");
    EXPECT_EQ(first_error("let f = 3\nlet y = f(1)"), "'f' is a number, not a function");
    EXPECT_EQ(first_error("sqrt(4)"),
              "'sqrt' is a built-in function: it gives a value and makes no blocks; use its value, as in 'let x = "
              "sqrt(...)'");
    EXPECT_EQ(first_error("return 1"), "'return' is written inside a function's body (fn)");
}

TEST(Language, BooleansAndConditionsAreTheirOwnType) {
    EXPECT_EQ(radius_of("", "if 1 < 2 and not (3 >= 4) { 1 } else { 2 }"), 1);
    EXPECT_EQ(radius_of("", "if 1 == 2 or 2 != 2 { 1 } else if true { 3 } else { 2 }"), 3);
    EXPECT_EQ(radius_of("let v = (1, 2, 3)", "if v == (1, 2, 3) and \"a\" != \"b\" { 4 } else { 5 }"), 4);
    EXPECT_EQ(first_error("let x = if 1 { 2 } else { 3 }"),
              "a condition must be true or false; this is a number (compare it, as in 'x != 0')");
    EXPECT_EQ(first_error("let x = 1 < 2 < 3"), "comparisons do not chain: write 'a < b and b < c'");
    EXPECT_EQ(first_error("let x = 1 == (1, 2, 3)"),
              "'==' compares two values of the same kind; this is a number and a vector of 3 numbers");
    EXPECT_EQ(first_error("let x = (1, 2, 3) < (2, 3, 4)"), "'<' compares numbers; this is a vector of 3 numbers");
    EXPECT_EQ(first_error("if x = 1 { }"), "'=' gives a name its value; to compare two values write '=='");
    EXPECT_EQ(first_error("let x = 1 && 2"), "unexpected character '&'; for both conditions write 'and'");
    // 'and' and 'or' stop at the first operand that decides: the rest is not evaluated.
    EXPECT_EQ(radius_of("", "if false and 1 / 0 > 0 { 2 } else { 1 }"), 1);
    // An if statement picks which blocks are made.
    LoadResult r = load(
        "for i in 0..4 {\n  if mod(i, 2) == 0 { sphere { center (i, 0, 0) radius 0.1 material { kd 1 } } }\n"
        "  else { sphere { center (i, 0, 0) radius 0.2 material { kd 1 } } }\n}");
    ASSERT_TRUE(r.scene);
    ASSERT_EQ(r.scene->spheres.size(), 4u);
    EXPECT_EQ(r.scene->spheres[1].radius, 0.2);
    EXPECT_EQ(r.scene->spheres[2].radius, 0.1);
}

TEST(Language, ListsHoldValuesAndLoopsRunOverThem) {
    EXPECT_EQ(radius_of("let l = [0.5, (1, 2, 3), \"s\", [4]]", "l[0] + l[1].y + len(l) + l[3][0]"), 10.5);
    EXPECT_EQ(radius_of("let v = (1, 2, 3)", "v[2]"), 3);
    LoadResult r = load("for c in [(0, 0, 0), (1, 0, 0)] { sphere { center c radius 0.25 material { kd 1 } } }");
    ASSERT_TRUE(r.scene);
    ASSERT_EQ(r.scene->spheres.size(), 2u);
    EXPECT_EQ(r.scene->spheres[1].center, dvec3(1, 0, 0));
    EXPECT_EQ(first_error("let l = [1, 2]\nlet x = l[2]"),
              "index 2 is past the end: a list of 2 values has indexes 0 to 1");
    EXPECT_EQ(first_error("let l = [1, 2]\nlet x = l[-1]"), "an index is a whole number from 0; this is -1");
    EXPECT_EQ(first_error("let l = [1, 2]\nsphere { center (0, 0, 0) radius l material { kd 1 } }"),
              "'radius' takes one value, not a list; pick one with [i], as in 'list[0]'");
    EXPECT_EQ(first_error("for x in 3 { }"), "'for x in' takes a range A..B or a list; this is a number");
}

TEST(Language, LetHoldsStringsAndTransforms) {
    LoadResult r = load("let path = \"" + std::string(TRACER_SOURCE_DIR) +
                        "/scenes/meshes/tetrahedron.obj\"\nlet up = transform { translate (0, 2, 0) }\n"
                        "mesh { file path transform up material { kd 1 } }");
    ASSERT_EQ(errors(r).size(), 0u) << errors(r)[0];
    ASSERT_TRUE(r.scene);
    ASSERT_EQ(r.scene->meshes.size(), 1u);
    ASSERT_EQ(r.scene->meshes[0].steps.size(), 1u);
    EXPECT_EQ(r.scene->meshes[0].steps[0].vector, dvec3(0, 2, 0));
}

TEST(Language, GroupsComposeTheirPlacementsInnerFirst) {
    LoadResult r = load(
        "group {\n  translate (1, 0, 0)\n  group {\n    rotate { axis (0, 0, 1) angle 90 }\n    scale 2\n"
        "    sphere { center (1, 0, 0) radius 0.5 material { kd 1 } }\n"
        "    box { min (0, 0, 0) max (1, 1, 1) translate (0, 0, 1) material { kd 1 } }\n"
        "    light { position (1, 0, 0) }\n  }\n}");
    ASSERT_TRUE(r.scene) << errors(r)[0];
    const Sphere& sphere = r.scene->spheres.at(0);
    EXPECT_NEAR(sphere.center.x, 1, 1e-15);  // (1,0,0) scaled to (2,0,0), turned to (0,2,0), moved to (1,2,0)
    EXPECT_NEAR(sphere.center.y, 2, 1e-15);
    EXPECT_EQ(sphere.radius, 1);
    EXPECT_NEAR(r.scene->lights.at(1).position.y, 2, 1e-15);
    // The box: its own translate first, then the inner group, then the outer one.
    const Placement box(r.scene->boxes.at(0));
    const dvec3 corner = box.point(dvec3(0, 0, 0));
    EXPECT_NEAR(corner.x, 1, 1e-15);
    EXPECT_NEAR(corner.y, 0, 1e-15);
    EXPECT_NEAR(corner.z, 2, 1e-15);
    EXPECT_EQ(first_error("group { scale (1, 2, 1)\n sphere { center (0, 0, 0) radius 1 material { kd 1 } } }"),
              "this scales a sphere by different factors on different axes, which would make an ellipsoid; tracer "
              "draws spheres only: scale it by one factor, or use a mesh");
    EXPECT_EQ(radius_of("", "1\n scale -3 rotate { angle 30 }"), 3);  // a sphere's own placement
}

TEST(Language, AValueFromTheCommandLineSaysSoWhereItIsRefused) {
    const LoadResult r = load_scene_text(
        "/scenes/t.scn",
        kCamera + "param r = 1\nfor i in 0..3 { sphere { center (i, 0, 0) radius r material { kd 1 } } }", false,
        ParameterValues{{"r", "-1"}}, {});
    ASSERT_EQ(errors(r).size(), 1u);
    const Diagnostic& d = r.diagnostics.all()[0];
    EXPECT_EQ(d.message, "'radius' must be greater than 0, found -1");
    ASSERT_GE(d.notes.size(), 2u);
    EXPECT_EQ(d.notes[0].message, "this value came from the command line: -D r=-1");
    EXPECT_EQ(d.notes[1].message, "in iteration i = 0 of this loop");
    EXPECT_EQ(d.repeats, 2);  // the other iterations, counted as iterations
    EXPECT_EQ(d.repeated_in, Diagnostic::RepeatedIn::Iterations);
}

// Blocks whose spans nothing kept let the interpreter forget the contexts made for them; a span
// kept for a later message (a material used before its block) keeps its iteration.
TEST(Language, AnErrorFoundAfterTheLoopStillNamesItsIteration) {
    const LoadResult r = load(
        "for i in 0..3 {\n  sphere { center (i, 0, 0) radius 0.2 material { kd 1 } }\n"
        "  sphere { center (i, 1, 0) radius 0.2 material later }\n}\nlet after = 1\n"
        "sphere { center (0, 0, 0) radius 0.2 - 0.1 * after * 2 material { kd 1 } }");
    ASSERT_EQ(errors(r).size(), 2u);
    for (const Diagnostic& d : r.diagnostics.all()) {
        if (d.message == "undefined material 'later'") {
            ASSERT_EQ(d.notes.size(), 1u);
            EXPECT_EQ(d.notes[0].message, "in iteration i = 0 of this loop");
            EXPECT_EQ(d.repeats, 2);
        } else {
            EXPECT_EQ(d.message, "'radius' must be greater than 0, found 0");
            EXPECT_EQ(d.notes.size(), 0u);  // outside the loop: no stale context
        }
    }
}

}  // namespace
}  // namespace tracer
