// The grammar reference cannot drift from the parser: it is generated from the block tables,
// and every example in grammar/ must parse and validate.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "lang/load_scene.h"
#include "lang/reference_doc.h"
#include "lang/schema.h"

namespace tracer {
namespace {

namespace fs = std::filesystem;
const fs::path kGrammarDir = fs::path(TRACER_SOURCE_DIR) / "grammar";

std::string read(const fs::path& path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

std::string all_messages(const LoadResult& result) {
    std::string out;
    for (const Diagnostic& d : result.diagnostics.all()) out += format_diagnostic(d);
    return out;
}

TEST(Reference, CommittedReferenceMatchesTheTables) {
    EXPECT_EQ(read(kGrammarDir / "reference.md"), reference_markdown())
        << "grammar/reference.md is out of date: run  build/release/tracer --reference > grammar/reference.md";
}

TEST(Reference, EveryDefaultPassesItsOwnChecks) {
    for (const BlockSpec* spec : all_block_specs()) {
        if (!spec->top_level) continue;
        std::string text = std::string(spec->kind) + (spec->named ? " x" : "") + " {\n";
        for (const KeySpec& key : spec->keys)
            if (!key.required()) text += "  " + std::string(key.name) + " " + std::string(key.default_value) + "\n";
        text += "}\n";
        LoadResult result = load_scene_text("defaults.scn", text, /*fragment=*/true);
        for (const Diagnostic& d : result.diagnostics.all())
            EXPECT_NE(d.message.find("missing the required key"), std::string::npos)
                << "default of a '" << spec->kind << "' key fails its own check:\n"
                << format_diagnostic(d);
    }
}

TEST(Reference, EveryExampleInGrammarParsesAndValidates) {
    int examples = 0;
    for (const auto& entry : fs::directory_iterator(kGrammarDir)) {
        if (entry.path().extension() != ".md") continue;
        std::istringstream lines(read(entry.path()));
        std::string line, example;
        bool inside = false;
        int start_line = 0, line_number = 0;
        while (std::getline(lines, line)) {
            ++line_number;
            if (!inside && line == "```scn") {
                inside = true;
                example.clear();
                start_line = line_number;
            } else if (inside && line == "```") {
                inside = false;
                ++examples;
                // Named as if it lived in grammar/, so relative paths resolve from there.
                LoadResult result = load_scene_text((kGrammarDir / "example.scn").string(), example, true);
                EXPECT_TRUE(result.scene && result.diagnostics.warning_count() == 0)
                    << entry.path().filename() << ", example at line " << start_line << ":\n"
                    << all_messages(result);
            } else if (inside) {
                example += line + "\n";
            }
        }
        EXPECT_FALSE(inside) << entry.path() << ": unterminated ```scn block";
    }
    EXPECT_GE(examples, 8);  // one per block kind at least
}

}  // namespace
}  // namespace tracer
