// Bad input is normal input: thousands of random edits of a real scene must never crash or
// hang the front end, and a scene comes back exactly when no error was reported.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "lang/load_scene.h"

namespace tracer {
namespace {

std::string read_scene(const std::string& name) {
    std::ifstream in(std::filesystem::path(TRACER_SOURCE_DIR) / "scenes" / name);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}
std::string read_task2() {
    return read_scene("task2.scn");
}

TEST(Fuzz, RandomEditsOfTask2NeverCrashAndAreConsistent) {
    const std::string original = read_task2();
    ASSERT_FALSE(original.empty());
    const std::string alphabet = "{}(),#\"-+.e0123456789 \n\tabcxyz_\\\x01\xff";
    std::mt19937 random(12345);
    int rejected = 0;
    for (int round = 0; round < 3000; ++round) {
        std::string text = original;
        int edits = 1 + int(random() % 4);
        for (int e = 0; e < edits && !text.empty(); ++e) {
            size_t at = random() % text.size();
            switch (random() % 3) {
                case 0: text.erase(at, 1 + random() % 8); break;
                case 1: text.insert(at, 1, alphabet[random() % alphabet.size()]); break;
                default: text[at] = alphabet[random() % alphabet.size()]; break;
            }
        }
        LoadResult result = load_scene_text("fuzz.scn", text);
        EXPECT_EQ(bool(result.scene), !result.diagnostics.has_errors()) << text;
        EXPECT_LE(result.diagnostics.error_count(), Diagnostics::kMaxErrors);
        for (const Diagnostic& d : result.diagnostics.all()) format_diagnostic(d);  // must not crash either
        rejected += result.scene ? 0 : 1;
    }
    EXPECT_GT(rejected, 1000);  // the edits really do break scenes
}

// The same for a program: names, a parameter, expressions, nested loops (scenes/chessboard.scn),
// edited with the operators too; small generation limits keep every round fast.
TEST(Fuzz, RandomEditsOfAProgramNeverCrashAndAreConsistent) {
    const std::string original = read_scene("chessboard.scn");
    ASSERT_FALSE(original.empty());
    const std::string alphabet = "{}(),#\"-+*/=.e0123456789 \n\tabcijxyz_\x01\xff";
    const std::string words[] = {"let ", "for ", " in ", "..", "param ", "include \"x.scn\" ", "sqrt(", ".x"};
    InterpretLimits limits;
    limits.max_blocks = 5000;
    limits.max_iterations = 20000;
    std::mt19937 random(54321);
    int rejected = 0;
    for (int round = 0; round < 1500; ++round) {
        std::string text = original;
        int edits = 1 + int(random() % 4);
        for (int e = 0; e < edits && !text.empty(); ++e) {
            size_t at = random() % text.size();
            switch (random() % 4) {
                case 0: text.erase(at, 1 + random() % 8); break;
                case 1: text.insert(at, 1, alphabet[random() % alphabet.size()]); break;
                case 2: text.insert(at, words[random() % std::size(words)]); break;
                default: text[at] = alphabet[random() % alphabet.size()]; break;
            }
        }
        LoadResult result = load_scene_text("fuzz.scn", text, false, {}, limits);
        EXPECT_EQ(bool(result.scene), !result.diagnostics.has_errors()) << text;
        for (const Diagnostic& d : result.diagnostics.all()) format_diagnostic(d);
        rejected += result.scene ? 0 : 1;
    }
    EXPECT_GT(rejected, 300);
}

// Deep parentheses, signs and loops are errors, not a stack overflow.
TEST(Fuzz, DeeplyNestedExpressionsAndLoopsAreAnError) {
    const std::string cases[] = {"let a = " + std::string(100000, '(') + "1",
                                 "let a = " + std::string(100000, '-') + "1", [] {
                                     std::string loops;
                                     for (int i = 0; i < 100000; ++i) loops += "for i in 0..1 { ";
                                     return loops;
                                 }()};
    for (const std::string& text : cases) {
        LoadResult result = load_scene_text("deep.scn", text);
        EXPECT_FALSE(result.scene);
        ASSERT_GE(result.diagnostics.error_count(), 1);
        EXPECT_NE(result.diagnostics.all()[0].message.find("nested too deeply (more than 200"), std::string::npos)
            << result.diagnostics.all()[0].message;
    }
}

// The limits count loops and expressions apart: 200 nested loops around a parenthesised
// expression are within them (they were refused as "the expression is nested too deeply").
TEST(Fuzz, TwoHundredNestedLoopsAroundAnExpressionAreWithinTheLimits) {
    auto nested = [](int loops) {
        std::string text = "camera { eye (0, 0, 7) lookat (0, 0, 0) }\nlight { position (0, 5, 5) }\n";
        for (int i = 0; i < loops; ++i) text += "for i" + std::to_string(i) + " in 0..1 {\n";
        text += "sphere { center ((i0 + 1) * 2, 0, 0) radius 1 material { kd 1 } }\n";
        for (int i = 0; i < loops; ++i) text += "}\n";
        return text;
    };
    LoadResult within = load_scene_text("deep.scn", nested(200));
    EXPECT_TRUE(within.scene) << within.diagnostics.all()[0].message;
    LoadResult beyond = load_scene_text("deep.scn", nested(201));
    ASSERT_FALSE(beyond.scene);
    EXPECT_EQ(beyond.diagnostics.all()[0].message, "statements are nested too deeply (more than 200 levels)");
}

TEST(Fuzz, DeeplyNestedBracesAreAnErrorNotAStackOverflow) {
    std::string text = "sphere ";
    for (int i = 0; i < 100000; ++i) text += "{ a ";
    LoadResult result = load_scene_text("deep.scn", text);
    EXPECT_FALSE(result.scene);
    ASSERT_GE(result.diagnostics.error_count(), 1);
    EXPECT_EQ(result.diagnostics.all()[0].message, "blocks are nested too deeply (more than 16 levels)");
}

}  // namespace
}  // namespace tracer
