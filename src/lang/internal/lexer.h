// The scene language's tokens: identifiers, numbers, strings, { } ( ) , and the operators
// + - * / = [ ] == != < <= > >= . .. Comments run from '#' to the end of the line. Bad characters and malformed numbers
// are reported once and come back as Error tokens, so the parser never sees them twice.
#pragma once

#include <string>
#include <string_view>

#include "base/diagnostics.h"
#include "base/source.h"

namespace tracer {

enum class TokenKind {
    Identifier,
    Number,
    String,
    LBrace,
    RBrace,
    LParen,
    RParen,
    Comma,
    Plus,
    Minus,
    Star,
    Slash,
    Equals,
    LBracket,
    RBracket,
    EqualsEquals,  // ==
    NotEquals,     // !=
    Less,
    LessEquals,
    Greater,
    GreaterEquals,
    Dot,
    DotDot,
    End,
    Error
};

struct Token {
    TokenKind kind = TokenKind::End;
    Span span;
    std::string_view text;  // the token as written
    double number = 0;      // Number: its value (always finite, never negative: a sign is an operator)
    std::string string;     // String: the contents with escapes resolved
};

// A readable name for a token kind, for messages ("'{'", "a number", ...).
std::string describe(TokenKind kind);
// A readable description of one token as written ("'radius'", "end of file").
std::string describe(const Token& token);

class Lexer {
public:
    // Spans of the tokens carry `origin` (Sources: which file, and in what context).
    Lexer(const SourceFile& file, Diagnostics& diagnostics, uint32_t origin = 0);

    // Returns the next token, reporting and skipping over anything malformed.
    Token next();
    // While quiet, malformed input still becomes Error tokens but is not reported (used
    // while the parser skips the rest of a block it has already reported).
    void set_quiet(bool quiet) { quiet_ = quiet; }

private:
    Token make(TokenKind kind, uint32_t begin);
    void report(Span span, std::string message);
    Token lex_number(uint32_t begin);
    Token lex_string(uint32_t begin);
    Token lex_comparison(uint32_t begin);
    void skip_space_and_comments();

    const SourceFile& file_;
    Diagnostics& diagnostics_;
    std::string_view text_;
    uint32_t pos_ = 0;
    uint32_t last_end_ = 0;  // end of the last token, where "end of file" is shown
    bool quiet_ = false;
    uint32_t origin_ = 0;
    // Comments that look like another language's directives, already warned about.
    void warn_about_directive(uint32_t begin);
};

}  // namespace tracer
