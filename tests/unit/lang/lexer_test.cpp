#include <gtest/gtest.h>

#include <vector>

#include "lang/internal/lexer.h"

namespace tracer {
namespace {

struct Lexed {
    std::vector<Token> tokens;
    Diagnostics diagnostics;
};

Lexed lex(const std::string& text) {
    Lexed out;
    SourceFile file("t.scn", text);
    Lexer lexer(file, out.diagnostics);
    for (;;) {
        Token token = lexer.next();
        token.text = {};  // the view points into `file`, which dies here
        out.tokens.push_back(token);
        if (token.kind == TokenKind::End) break;
    }
    return out;
}

double number_of(const std::string& text) {
    Lexed lexed = lex(text);
    EXPECT_EQ(lexed.tokens.size(), 2u) << text;
    EXPECT_EQ(lexed.tokens[0].kind, TokenKind::Number) << text;
    EXPECT_FALSE(lexed.diagnostics.has_errors()) << text;
    return lexed.tokens[0].number;
}

TEST(Lexer, NumbersInEveryDecimalAndExponentForm) {
    EXPECT_EQ(number_of("3"), 3.0);
    EXPECT_EQ(number_of(".25"), 0.25);
    EXPECT_EQ(number_of("4."), 4.0);
    EXPECT_EQ(number_of("1e-3"), 1e-3);
    EXPECT_EQ(number_of("1E+2"), 100.0);
    EXPECT_EQ(number_of("2.5e2"), 250.0);
    EXPECT_EQ(number_of("0.1"), 0.1);  // correctly rounded, locale-independent
}

// A sign is an operator (the parser makes -0.5 a negation); ".." ends a number (a range).
TEST(Lexer, SignsDotsAndRangesAreOperators) {
    using K = TokenKind;
    auto kinds_of = [](const std::string& text) {
        std::vector<K> kinds;
        for (const Token& t : lex(text).tokens) kinds.push_back(t.kind);
        return kinds;
    };
    EXPECT_EQ(kinds_of("-0.5"), (std::vector<K>{K::Minus, K::Number, K::End}));
    EXPECT_EQ(kinds_of("+2*3/4=5"), (std::vector<K>{K::Plus, K::Number, K::Star, K::Number, K::Slash, K::Number,
                                                    K::Equals, K::Number, K::End}));
    EXPECT_EQ(kinds_of("0..8"), (std::vector<K>{K::Number, K::DotDot, K::Number, K::End}));
    EXPECT_EQ(kinds_of("1...5"), (std::vector<K>{K::Number, K::DotDot, K::Number, K::End}));  // 1 .. .5
    EXPECT_EQ(kinds_of("v.x"), (std::vector<K>{K::Identifier, K::Dot, K::Identifier, K::End}));
    EXPECT_EQ(lex("0..8").tokens[2].number, 8);
}

// Other languages' directives are comments here, with a warning saying what to write instead.
TEST(Lexer, DirectivesOfOtherLanguagesAreCommentsWithAHint) {
    Lexed lexed = lex("#include \"colors.inc\"\n#declare R = 0.5;\n#includes are fine\n# include\n");
    ASSERT_EQ(lexed.diagnostics.warning_count(), 2);
    EXPECT_EQ(lexed.diagnostics.all()[0].message,
              "'#' starts a comment, so this line is ignored; write include \"file.scn\"");
    EXPECT_EQ(lexed.diagnostics.all()[1].message,
              "'#' starts a comment, so this line is ignored; write let NAME = value");
    EXPECT_EQ(lexed.tokens.size(), 1u);  // all comments
}

TEST(Lexer, TinyNumbersUnderflowToZeroButHugeOnesAreErrors) {
    EXPECT_EQ(number_of("1e-999"), 0.0);
    Lexed huge = lex("1e999");
    EXPECT_EQ(huge.tokens[0].kind, TokenKind::Error);
    ASSERT_EQ(huge.diagnostics.error_count(), 1);
    EXPECT_EQ(huge.diagnostics.all()[0].message, "number '1e999' is out of range (it would be infinite)");
}

TEST(Lexer, MalformedNumbersAreOneErrorEach) {
    for (const char* text : {"1.2.3", "3x", "1e", "1e+"}) {
        Lexed lexed = lex(text);
        EXPECT_EQ(lexed.diagnostics.error_count(), 1) << text;
        EXPECT_EQ(lexed.tokens[0].kind, TokenKind::Error) << text;
        EXPECT_EQ(lexed.tokens.size(), 2u) << text;  // the whole thing is one token
    }
}

TEST(Lexer, PunctuationIdentifiersStringsAndComments) {
    Lexed lexed = lex("sphere_2 { # a comment { ( \n (1, \"a \\\"b\\\" \\\\c\") }");
    std::vector<TokenKind> kinds;
    for (const Token& t : lexed.tokens) kinds.push_back(t.kind);
    using K = TokenKind;
    EXPECT_EQ(kinds, (std::vector<K>{K::Identifier, K::LBrace, K::LParen, K::Number, K::Comma, K::String, K::RParen,
                                     K::RBrace, K::End}));
    EXPECT_EQ(lexed.tokens[5].string, "a \"b\" \\c");
    EXPECT_FALSE(lexed.diagnostics.has_errors());
}

TEST(Lexer, UnterminatedStringStopsAtTheLineEnd) {
    Lexed lexed = lex("file \"abc\nradius 1");
    EXPECT_EQ(lexed.diagnostics.error_count(), 1);
    EXPECT_EQ(lexed.tokens[1].kind, TokenKind::Error);
    EXPECT_EQ(lexed.tokens[2].kind, TokenKind::Identifier);  // lexing resumes on the next line
}

TEST(Lexer, UnexpectedCharacterIsReportedWhole) {
    Lexed lexed = lex("radius \xc2\xb5 1");  // a UTF-8 micro sign
    ASSERT_EQ(lexed.diagnostics.error_count(), 1);
    EXPECT_EQ(lexed.diagnostics.all()[0].message, "unexpected character '\xc2\xb5'");
    EXPECT_EQ(lexed.tokens[2].kind, TokenKind::Number);
}

TEST(Lexer, LineAndColumnAreComputedFromOffsets) {
    SourceFile file("t.scn", "a\n  bc\n\nd");
    EXPECT_EQ(file.locate(0).line, 1);
    EXPECT_EQ(file.locate(4).line, 2);
    EXPECT_EQ(file.locate(4).column, 3);
    EXPECT_EQ(file.locate(9).line, 4);
    EXPECT_EQ(file.line_text(2), "  bc");
    EXPECT_EQ(file.line_text(3), "");
}

}  // namespace
}  // namespace tracer
