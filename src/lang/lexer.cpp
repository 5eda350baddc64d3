#include "lang/internal/lexer.h"

#include <charconv>
#include <cmath>
#include <cstdlib>

#include "base/portable.h"

namespace tracer {

static bool is_ident_start(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
static bool is_digit(char c) {
    return c >= '0' && c <= '9';
}
static bool is_ident_char(char c) {
    return is_ident_start(c) || is_digit(c);
}

// The length of the UTF-8 letter at the start of `text` (Latin, Greek or Cyrillic, as in a name
// written in another language: 'größe', 'é', 'радиус'), or 0 if it starts with anything else.
static size_t utf8_letter_length(std::string_view text) {
    if (text.size() < 2) return 0;
    const unsigned char a = static_cast<unsigned char>(text[0]), b = static_cast<unsigned char>(text[1]);
    if ((a & 0xE0) != 0xC0 || (b & 0xC0) != 0x80) return 0;
    const unsigned code = (unsigned(a & 0x1F) << 6) | unsigned(b & 0x3F);
    const bool letter = (code >= 0xC0 && code <= 0x24F && code != 0xD7 && code != 0xF7) ||  // not x and /
                        (code >= 0x370 && code <= 0x4FF);
    return letter ? 2 : 0;
}

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
        case TokenKind::Plus: return "'+'";
        case TokenKind::Minus: return "'-'";
        case TokenKind::Star: return "'*'";
        case TokenKind::Slash: return "'/'";
        case TokenKind::Equals: return "'='";
        case TokenKind::LBracket: return "'['";
        case TokenKind::RBracket: return "']'";
        case TokenKind::EqualsEquals: return "'=='";
        case TokenKind::NotEquals: return "'!='";
        case TokenKind::Less: return "'<'";
        case TokenKind::LessEquals: return "'<='";
        case TokenKind::Greater: return "'>'";
        case TokenKind::GreaterEquals: return "'>='";
        case TokenKind::Dot: return "'.'";
        case TokenKind::DotDot: return "'..'";
        case TokenKind::End: return "end of file";
        case TokenKind::Error: return "an invalid token";
    }
    return "a token";
}

std::string describe(const Token& token) {
    if (token.kind == TokenKind::End) return "end of file";
    return in_quotes(token.text);
}

Lexer::Lexer(const SourceFile& file, Diagnostics& diagnostics, uint32_t origin)
    : file_(file), diagnostics_(diagnostics), text_(file.text()), origin_(origin) {}

void Lexer::report(Span span, std::string message) {
    if (!quiet_) diagnostics_.error(file_, span, std::move(message));
}

Token Lexer::make(TokenKind kind, uint32_t begin) {
    Token token;
    token.kind = kind;
    token.span = {begin, pos_, origin_};
    token.text = text_.substr(begin, pos_ - begin);
    last_end_ = pos_;
    return token;
}

void Lexer::skip_space_and_comments() {
    while (pos_ < text_.size()) {
        char c = text_[pos_];
        if (c == '#') {
            warn_about_directive(pos_);
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
        end.span = {after_last_token, after_last_token, origin_};
        return end;
    }

    char c = text_[pos_];
    switch (c) {
        case '{': ++pos_; return make(TokenKind::LBrace, begin);
        case '}': ++pos_; return make(TokenKind::RBrace, begin);
        case '(': ++pos_; return make(TokenKind::LParen, begin);
        case ')': ++pos_; return make(TokenKind::RParen, begin);
        case ',': ++pos_; return make(TokenKind::Comma, begin);
        case '+': ++pos_; return make(TokenKind::Plus, begin);
        case '-': ++pos_; return make(TokenKind::Minus, begin);
        case '*': ++pos_; return make(TokenKind::Star, begin);
        case '/': ++pos_; return make(TokenKind::Slash, begin);
        case '[': ++pos_; return make(TokenKind::LBracket, begin);
        case ']': ++pos_; return make(TokenKind::RBracket, begin);
        case '=':
        case '<':
        case '>':
        case '!': return lex_comparison(begin);
        case '"': return lex_string(begin);
        default: break;
    }
    if (is_ident_start(c) || utf8_letter_length(text_.substr(begin))) {
        bool ascii = true;
        while (pos_ < text_.size()) {
            if (is_ident_char(text_[pos_])) {
                ++pos_;
            } else if (const size_t letter = utf8_letter_length(text_.substr(pos_))) {
                pos_ += letter;
                ascii = false;
            } else {
                break;
            }
        }
        if (ascii) return make(TokenKind::Identifier, begin);
        Token bad = make(TokenKind::Error, begin);
        report(bad.span, in_quotes(bad.text) + ": names are ASCII letters, digits and _");
        return bad;
    }
    if (c == '.' && !(pos_ + 1 < text_.size() && is_digit(text_[pos_ + 1]))) {
        pos_ += pos_ + 1 < text_.size() && text_[pos_ + 1] == '.' ? 2 : 1;
        return make(pos_ - begin == 2 ? TokenKind::DotDot : TokenKind::Dot, begin);
    }
    if (is_digit(c) || c == '.') return lex_number(begin);

    // Skip a whole UTF-8 sequence so the message shows the character, not one of its bytes.
    ++pos_;
    while (pos_ < text_.size() && (static_cast<unsigned char>(text_[pos_]) & 0xC0) == 0x80) ++pos_;
    Token bad = make(TokenKind::Error, begin);
    // Operators of other languages, with the way to write them here.
    const std::string hint = bad.text == "%"   ? "; for the remainder of a / b write mod(a, b)"
                             : bad.text == "^" ? "; for a to the power b write pow(a, b)"
                             : bad.text == "&" ? "; for both conditions write 'and'"
                             : bad.text == "|" ? "; for either condition write 'or'"
                             : bad.text == "?" ? "; a value chosen by a condition is if CONDITION { A } else { B }"
                                               : "";
    report(bad.span, "unexpected character " + in_quotes(bad.text) + hint);
    return bad;
}

// = == < <= > >= != and a lone '!' (an error: 'not' is written as a word).
Token Lexer::lex_comparison(uint32_t begin) {
    const char first = text_[pos_++];
    const bool equals_follows = pos_ < text_.size() && text_[pos_] == '=';
    if (equals_follows) ++pos_;
    switch (first) {
        case '=': return make(equals_follows ? TokenKind::EqualsEquals : TokenKind::Equals, begin);
        case '<': return make(equals_follows ? TokenKind::LessEquals : TokenKind::Less, begin);
        case '>': return make(equals_follows ? TokenKind::GreaterEquals : TokenKind::Greater, begin);
        default: break;
    }
    if (equals_follows) return make(TokenKind::NotEquals, begin);
    Token bad = make(TokenKind::Error, begin);
    report(bad.span, "unexpected character '!'; a condition is negated by 'not': not (a < b)");
    return bad;
}

// True if a number that from_chars found out of range is too large (not too small).
static bool overflows(std::string_view text) {
    // strtod tells the two apart (HUGE_VAL vs 0); the program runs in the "C" locale.
    return std::isinf(std::strtod(std::string(text).c_str(), nullptr));
}

// number = ( digits [ "." { digit } ] | "." digits ) [ ( "e" | "E" ) [ "+" | "-" ] digits ]
// ("0..8" is 0, "..", 8: a dot followed by a dot ends the number).
Token Lexer::lex_number(uint32_t begin) {
    auto digits = [&] {
        uint32_t start = pos_;
        while (pos_ < text_.size() && is_digit(text_[pos_])) ++pos_;
        return pos_ > start;
    };
    auto range_follows = [&] { return pos_ + 1 < text_.size() && text_[pos_ + 1] == '.'; };
    bool ok = digits();
    if (pos_ < text_.size() && text_[pos_] == '.' && !range_follows()) {
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
    while (pos_ < text_.size() && (is_ident_char(text_[pos_]) || (text_[pos_] == '.' && !range_follows()))) {
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
    auto [end, status] = parse_double(digits_text.data(), digits_text.data() + digits_text.size(), token.number);
    if (status == std::errc::result_out_of_range && !overflows(digits_text)) {
        token.number = 0;  // underflow: tiny numbers round to zero, as everywhere else
    } else if (status != std::errc() || end != digits_text.data() + digits_text.size() ||
               !std::isfinite(token.number)) {
        token.kind = TokenKind::Error;
        report(token.span, "number " + in_quotes(token.text) + " is out of range (it would be infinite)");
    }
    return token;
}

// Other scene languages' directives, written out of habit, are comments here: say so once each.
void Lexer::warn_about_directive(uint32_t begin) {
    static const std::pair<std::string_view, std::string_view> kHints[] = {
        {"#include", "write include \"file.scn\""},
        {"#declare", "write let NAME = value"},
        {"#local", "write let NAME = value"},
        {"#for", "write for NAME in A..B { ... }"},
        {"#while", "write while CONDITION { ... }"},
        {"#if", "write if CONDITION { ... } else { ... }"},
        {"#else", "write if CONDITION { ... } else { ... }"},
        {"#debug", "write print(...)"},
        {"#macro", "write fn NAME(A, B) { ... }"},
    };
    const std::string_view rest = text_.substr(begin);
    for (const auto& [directive, instead] : kHints) {
        if (rest.substr(0, directive.size()) != directive) continue;
        if (rest.size() > directive.size() && is_ident_char(rest[directive.size()])) continue;
        if (!quiet_)
            diagnostics_.warning(file_, {begin, begin + uint32_t(directive.size()), origin_},
                                 "'#' starts a comment, so this line is ignored; " + std::string(instead));
        return;
    }
}

// string = '"' { character other than '"', '\' or a line break | '\"' | '\\' } '"'
Token Lexer::lex_string(uint32_t begin) {
    ++pos_;
    std::string value;
    while (pos_ < text_.size() && text_[pos_] != '"' && text_[pos_] != '\n') {
        if (text_[pos_] == '\\' && pos_ + 1 < text_.size() && (text_[pos_ + 1] == '"' || text_[pos_ + 1] == '\\'))
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
