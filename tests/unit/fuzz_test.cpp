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

std::string read_task2() {
    std::ifstream in(std::filesystem::path(TRACER_SOURCE_DIR) / "scenes" / "task2.scn");
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
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
