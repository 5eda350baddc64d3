#include "lang/lexer.h"

#include <charconv>
#include <cmath>
#include <cstdlib>

namespace tracer {

static bool is_ident_start(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
static bool is_digit(char c) { return c >= '0' && c <= '9'; }
static bool is_ident_char(char c) { return is_ident_start(c) || is_digit(c); }

std::string describe(TokenKind kind) {
    switch (kind) {
        case TokenKind::Identifier: return "a name";
        case TokenKind::Number: return "a number";
        case TokenKind::String: return "a string";
        case TokenKind::LBrace: return "'{'";
        case TokenKind::RBrace: return "'}'";
        case TokenKind::LParen: return "'('";
        case TokenKind::RParen: return "')'";
        case TokenKind::Comma: return "','";
        case TokenKind::End: return "end of file";
        case TokenKind::Error: return "an invalid token";
    }
    return "a token";
}

std::string describe(const Token& token) {
    if (token.kind == TokenKind::End) return "end of file";
    return in_quotes(token.text);
}

Lexer::Lexer(const SourceFile& file, Diagnostics& diagnostics)
    : file_(file), diagnostics_(diagnostics), text_(file.text()) {}

void Lexer::report(Span span, std::string message) {
    if (!quiet_) diagnostics_.error(file_, span, std::move(message));
}

Token Lexer::make(TokenKind kind, uint32_t begin) {
    Token token;
    token.kind = kind;
    token.span = {begin, pos_};
    token.text = text_.substr(begin, pos_ - begin);
    last_end_ = pos_;
    return token;
}

void Lexer::skip_space_and_comments() {
    while (pos_ < text_.size()) {
        char c = text_[pos_];
        if (c == '#') {
            while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
        } else if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
            ++pos_;
        } else {
            return;
        }
    }
}

Token Lexer::next() {
    skip_space_and_comments();
    uint32_t begin = pos_;
    if (pos_ >= text_.size()) {
        const uint32_t after_last_token = last_end_;
        Token end = make(TokenKind::End, begin);
        end.span = {after_last_token, after_last_token};
        return end;
    }

    char c = text_[pos_];
    switch (c) {
        case '{': ++pos_; return make(TokenKind::LBrace, begin);
        case '}': ++pos_; return make(TokenKind::RBrace, begin);
        case '(': ++pos_; return make(TokenKind::LParen, begin);
        case ')': ++pos_; return make(TokenKind::RParen, begin);
        case ',': ++pos_; return make(TokenKind::Comma, begin);
        case '"': return lex_string(begin);
        default: break;
    }
    if (is_ident_start(c)) {
        while (pos_ < text_.size() && is_ident_char(text_[pos_])) ++pos_;
        return make(TokenKind::Identifier, begin);
    }
    bool starts_number = is_digit(c) || c == '.' ||
                         ((c == '-' || c == '+') && pos_ + 1 < text_.size() &&
                          (is_digit(text_[pos_ + 1]) || text_[pos_ + 1] == '.'));
    if (starts_number) return lex_number(begin);

    // Skip a whole UTF-8 sequence so the message shows the character, not one of its bytes.
    ++pos_;
    while (pos_ < text_.size() && (static_cast<unsigned char>(text_[pos_]) & 0xC0) == 0x80) ++pos_;
    Token bad = make(TokenKind::Error, begin);
    report(bad.span, "unexpected character " + in_quotes(bad.text));
    return bad;
}

// True if a number that from_chars found out of range is too large (not too small).
static bool overflows(std::string_view text) {
    // strtod tells the two apart (HUGE_VAL vs 0); the program runs in the "C" locale.
    return std::isinf(std::strtod(std::string(text).c_str(), nullptr));
}

// number = [ "+" | "-" ] ( digits [ "." { digit } ] | "." digits ) [ ( "e" | "E" ) [ "+" | "-" ] digits ]
Token Lexer::lex_number(uint32_t begin) {
    auto digits = [&] {
        uint32_t start = pos_;
        while (pos_ < text_.size() && is_digit(text_[pos_])) ++pos_;
        return pos_ > start;
    };
    if (text_[pos_] == '-' || text_[pos_] == '+') ++pos_;
    bool ok = digits();
    if (pos_ < text_.size() && text_[pos_] == '.') {
        ++pos_;
        ok = digits() || ok;
    }
    if (ok && pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
        ++pos_;
        if (pos_ < text_.size() && (text_[pos_] == '-' || text_[pos_] == '+')) ++pos_;
        ok = digits();
    }
    // A number glued to letters, digits or dots ("1.2.3", "3x") is one malformed token.
    bool glued = false;
    while (pos_ < text_.size() && (is_ident_char(text_[pos_]) || text_[pos_] == '.')) {
        ++pos_;
        glued = true;
    }
    Token token = make(TokenKind::Number, begin);
    if (!ok || glued) {
        token.kind = TokenKind::Error;
        report(token.span, "malformed number " + in_quotes(token.text));
        return token;
    }
    std::string_view digits_text = token.text;
    if (digits_text.front() == '+') digits_text.remove_prefix(1);
    auto [end, status] = std::from_chars(digits_text.data(), digits_text.data() + digits_text.size(),
                                         token.number);
    if (status == std::errc::result_out_of_range && !overflows(digits_text)) {
        token.number = 0;  // underflow: tiny numbers round to zero, as everywhere else
    } else if (status != std::errc() || end != digits_text.data() + digits_text.size() ||
               !std::isfinite(token.number)) {
        token.kind = TokenKind::Error;
        report(token.span, "number " + in_quotes(token.text) + " is out of range (it would be infinite)");
    }
    return token;
}

// string = '"' { character other than '"', '\' or a line break | '\"' | '\\' } '"'
Token Lexer::lex_string(uint32_t begin) {
    ++pos_;
    std::string value;
    while (pos_ < text_.size() && text_[pos_] != '"' && text_[pos_] != '\n') {
        if (text_[pos_] == '\\' && pos_ + 1 < text_.size() &&
            (text_[pos_ + 1] == '"' || text_[pos_ + 1] == '\\'))
            ++pos_;
        value += text_[pos_++];
    }
    if (pos_ >= text_.size() || text_[pos_] != '"') {
        Token bad = make(TokenKind::Error, begin);
        report(bad.span, "unterminated string (a string ends with '\"' on the same line)");
        return bad;
    }
    ++pos_;
    Token token = make(TokenKind::String, begin);
    token.string = std::move(value);
    return token;
}

}  // namespace tracer
