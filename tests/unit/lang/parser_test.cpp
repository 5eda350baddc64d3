#include <gtest/gtest.h>

#include "lang/internal/parser.h"
#include "lang/interpreter.h"

namespace tracer {
namespace {

struct Parsed {
    EvaluatedScene evaluated;
    Diagnostics diagnostics;
};

Parsed parse(const std::string& text) {
    Parsed out;
    Sources sources(std::make_unique<SourceFile>("t.scn", text));
    out.evaluated = interpret(sources, out.diagnostics);
    return out;
}

TEST(Parser, BlocksEntriesAndEveryKindOfValue) {
    Parsed p = parse(
        "material shiny { kd (0.2, 1, 0.2) n 100 }\n"
        "mesh { file \"a.obj\" rotate { axis (0, 1, 0) angle 30 } material shiny }");
    ASSERT_FALSE(p.diagnostics.has_errors());
    ASSERT_EQ(p.evaluated.blocks.size(), 2u);
    const Block& material = p.evaluated.blocks[0];
    EXPECT_EQ(material.kind, "material");
    EXPECT_EQ(material.name, "shiny");
    ASSERT_EQ(material.body.entries.size(), 2u);
    EXPECT_EQ(material.body.entries[0].value.kind, PlainValue::Kind::Vector);
    EXPECT_EQ(material.body.entries[0].value.components, (std::vector<double>{0.2, 1, 0.2}));
    EXPECT_EQ(material.body.entries[1].value.number, 100);
    const Block& mesh = p.evaluated.blocks[1];
    EXPECT_EQ(mesh.body.entries[0].value.kind, PlainValue::Kind::String);
    EXPECT_EQ(mesh.body.entries[0].value.text, "a.obj");
    ASSERT_EQ(mesh.body.entries[1].value.kind, PlainValue::Kind::Block);
    EXPECT_EQ(mesh.body.entries[1].value.body->entries.size(), 2u);
    EXPECT_EQ(mesh.body.entries[2].value.kind, PlainValue::Kind::Identifier);
}

TEST(Parser, RecoversAtBlockBoundariesWithOneErrorPerBrokenBlock) {
    Parsed p = parse(
        "sphere { center (0, 0 0) radius 1 }\n"  // missing comma
        "light { position (0, 1, 2) }\n"
        "plane { point (0, 0, 0) normal }\n"  // missing value
        "light { position (1, 1, 2) }\n");
    EXPECT_EQ(p.diagnostics.error_count(), 2);
    ASSERT_EQ(p.evaluated.blocks.size(), 4u);
    EXPECT_TRUE(p.evaluated.blocks[0].broken);
    EXPECT_FALSE(p.evaluated.blocks[1].broken);
    EXPECT_TRUE(p.evaluated.blocks[2].broken);
    EXPECT_FALSE(p.evaluated.blocks[3].broken);
}

TEST(Parser, UnclosedBlockAtEndOfFileGetsANoteAtItsBrace) {
    Parsed p = parse("camera {\n  eye (0, 0, 7)\n");
    ASSERT_EQ(p.diagnostics.error_count(), 1);
    const Diagnostic& d = p.diagnostics.all()[0];
    EXPECT_EQ(d.message, "expected '}' at end of file");
    ASSERT_EQ(d.notes.size(), 1u);
    EXPECT_EQ(d.notes[0].location.line, 1);
    EXPECT_EQ(d.notes[0].location.column, 8);
}

TEST(Parser, ANewBlockInsideABlockMeansAMissingBrace) {
    Parsed p = parse("camera { eye (0, 0, 7)\nsphere { radius 1 }\nmaterial m { }\n");
    ASSERT_EQ(p.diagnostics.error_count(), 1);
    EXPECT_EQ(p.diagnostics.all()[0].message, "expected '}' before 'sphere'");
    ASSERT_EQ(p.evaluated.blocks.size(), 3u);    // the sphere and the material still parse
    EXPECT_FALSE(p.evaluated.blocks[0].broken);  // its entries were complete
    EXPECT_EQ(p.evaluated.blocks[1].kind, "sphere");
}

TEST(Parser, InlineMaterialIsNotMistakenForANewBlock) {
    Parsed p = parse("sphere { material { kd 1 } radius 1 }");
    EXPECT_FALSE(p.diagnostics.has_errors());
}

TEST(Parser, StrayClosingBraceAtTopLevel) {
    Parsed p = parse("}\nlight { position (0, 0, 0) }");
    ASSERT_EQ(p.diagnostics.error_count(), 1);
    EXPECT_EQ(p.diagnostics.all()[0].message, "unexpected '}': no block is open here");
    EXPECT_EQ(p.evaluated.blocks.size(), 1u);
}

TEST(Parser, StopsAtTheErrorLimit) {
    std::string text;
    for (int i = 0; i < 500; ++i) text += "sphere { radius ( }\n";
    Parsed p = parse(text);
    EXPECT_EQ(p.diagnostics.error_count(), Diagnostics::kMaxErrorsFound);
}

}  // namespace
}  // namespace tracer
