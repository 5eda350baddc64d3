// The parser after a syntax error: skipping to where the next statement can start, so that one
// run reports the errors of several blocks, and telling a missing '}' from a new statement.
#include <algorithm>
#include <array>

#include "lang/internal/parser_class.h"
#include "lang/internal/suggest.h"
#include "lang/schema.h"

namespace tracer {

namespace {

// The words that begin a statement, and a group's placement keys (written before its statements).
constexpr std::array<std::string_view, 13> kStatementKeywords{"let",   "param",        "for",       "include", "if",
                                                              "fn",    "return",       "group",     "while",   "union",
                                                              "merge", "intersection", "difference"};
constexpr std::array<std::string_view, 4> kPlacementKeys{"scale", "rotate", "translate", "transform"};

}  // namespace

bool is_statement_keyword(std::string_view word) {
    return std::find(kStatementKeywords.begin(), kStatementKeywords.end(), word) != kStatementKeywords.end();
}

bool is_solid_keyword(std::string_view word) {
    return word == "union" || word == "merge" || word == "intersection" || word == "difference";
}

bool is_group_keyword(std::string_view word) {
    return word == "group" || is_solid_keyword(word);
}

bool makes_things(std::string_view word) {
    return is_group_keyword(word) ||
           (find_block_spec(word) && word != "material" && word != "render" && word != "camera");
}

bool is_placement_key(std::string_view word) {
    return std::find(kPlacementKeys.begin(), kPlacementKeys.end(), word) != kPlacementKeys.end();
}

void Parser::fail(const Token& token, std::string message) {
    // The lexer has already reported an Error token: one message per mistake.
    if (token.kind != TokenKind::Error) diagnostics_.error(file_, token.span, std::move(message));
    throw SyntaxError{};
}

// A top-level block written where a key was expected almost always means a missing '}':
// `sphere {`, `sphere name {` or `material name {` (a plain `material {` is an inline material),
// and so does a statement (`let x =`, `for i in`, `include "..."`).
bool Parser::starts_new_block() {
    if (!at(TokenKind::Identifier)) return false;
    std::string_view word = peek().text;
    if (is_statement_keyword(word)) return starts_statement();
    if (!find_block_spec(word)) return false;
    if (word != "material" && at(TokenKind::LBrace, 1)) return true;
    return at(TokenKind::Identifier, 1) && at(TokenKind::LBrace, 2);
}

// `let x =`, `param x =`, `for x in`, `include "..."`, `fn f(`, `group {`, `if`, `return`.
bool Parser::starts_statement() {
    if (!at(TokenKind::Identifier)) return false;
    std::string_view word = peek().text;
    if ((word == "let" || word == "param") && at(TokenKind::Identifier, 1) && at(TokenKind::Equals, 2)) return true;
    if (word == "for" && at(TokenKind::Identifier, 1) && at_word("in", 2)) return true;
    if (word == "fn") return at(TokenKind::Identifier, 1) && at(TokenKind::LParen, 2);
    if (is_group_keyword(word)) return at(TokenKind::LBrace, 1);
    if (word == "if" || word == "return") return true;
    return word == "include" && at(TokenKind::String, 1);
}

// Skips to the '}' that closes the current top-level block (or the end of the file).
void Parser::skip_to_block_end() {
    // The block is already reported: what the lexer finds in the rest of it is no news.
    lexer_.set_quiet(true);
    struct LoudAgain {
        Lexer& lexer;
        ~LoudAgain() { lexer.set_quiet(false); }
    } loud_again{lexer_};
    if (open_.empty()) {
        // The error came before the block's '{': skip to that brace, unless a block starts first.
        while (!at(TokenKind::End) && !at(TokenKind::LBrace) &&
               !(at(TokenKind::Identifier) && find_block_spec(peek().text)))
            take();
        if (!at(TokenKind::LBrace)) return;
        open_.push_back({take().span, "block"});
    }
    int depth = int(open_.size());
    while (depth > 0) {
        if (at(TokenKind::End) && gave_up_) return;  // reported already, and why the rest was skipped
        if (at(TokenKind::End)) {
            Diagnostic* d = diagnostics_.error(file_, peek().span, "expected '}' at end of file");
            Diagnostics::note(d, file_, open_.front().span,
                              "to close the '" + open_.front().owner + "' block opened here");
            return;
        }
        TokenKind kind = take().kind;
        if (kind == TokenKind::LBrace) ++depth;
        if (kind == TokenKind::RBrace) --depth;
    }
}

// `range(...)` where a range belongs: the way to write it here, from the call's own arguments.
std::string Parser::range_call_hint(const Expr& call, const std::string& name) const {
    auto text = [&](const Expr& e) { return std::string(file_.slice(e.span)); };
    const auto& args = call.operands;
    const std::string range = args.size() == 1   ? "0.." + text(args[0])
                              : args.size() == 2 ? text(args[0]) + ".." + text(args[1])
                                                 : "A..B";
    return "'range(...)' is not a function here: a loop is written 'for " + name + " in " + range +
           "' (from the first number up to the end - 1)";
}

// After an error in the header of a loop, condition, function or group: skip the statement,
// body and all, when its '{' is on the keyword's line (so that the body's statements and '}'
// raise no errors of their own); else as after any broken statement.
void Parser::skip_broken_header(Span keyword) {
    for (;;) {
        const int line = file_.locate(keyword.begin).line;
        lexer_.set_quiet(true);
        while (!at(TokenKind::End) && !at(TokenKind::LBrace) && file_.locate(peek().span.begin).line == line) take();
        lexer_.set_quiet(false);
        if (!at(TokenKind::LBrace)) return skip_to_next_statement();
        lexer_.set_quiet(true);
        for (int depth = 0; !at(TokenKind::End);) {
            const TokenKind kind = take().kind;
            depth += kind == TokenKind::LBrace ? 1 : kind == TokenKind::RBrace ? -1 : 0;
            if (depth == 0) break;
        }
        lexer_.set_quiet(false);
        // `} else {`: the rest of a broken condition goes with it.
        if (!at_word("else")) return;
        keyword = peek().span;
    }
}

// `word` begins no statement and no block follows it: said once, and the rest of its line (with
// what its brackets hold past the line) skipped.
void Parser::skip_unknown_statement(const Token& word) {
    std::vector<std::string_view> words;
    for (const BlockSpec* spec : all_block_specs())
        if (spec->top_level) words.push_back(spec->kind);
    words.insert(words.end(), kStatementKeywords.begin(), kStatementKeywords.end());
    words.insert(words.end(), kPlacementKeys.begin(), kPlacementKeys.end());
    const std::string hint = povray_hint(word.text);
    std::string message = "unknown word " + in_quotes(word.text) +
                          ": a statement begins with a block (sphere { ... }), a keyword (let, for, if, ...), "
                          "a call f(...) or an assignment NAME = value";
    const std::string suggestion = hint.empty() ? did_you_mean(word.text, words) : hint;
    if (!suggestion.empty()) message = "unknown word " + in_quotes(word.text) + suggestion;
    diagnostics_.error(file_, word.span, message);
    lexer_.set_quiet(true);
    const int line = file_.locate(word.span.begin).line;
    for (int depth = 0; !at(TokenKind::End);) {
        if (depth == 0 && (at(TokenKind::RBrace) || file_.locate(peek().span.begin).line != line)) break;
        const TokenKind taken = take().kind;
        depth += taken == TokenKind::LParen || taken == TokenKind::LBracket   ? 1
                 : taken == TokenKind::RParen || taken == TokenKind::RBracket ? -1
                                                                              : 0;
        if (depth < 0) depth = 0;
    }
    lexer_.set_quiet(false);
}

// After a broken statement: skip to what can start the next one (a statement keyword, a block
// kind, or a body's closing brace).
void Parser::skip_to_next_statement() {
    lexer_.set_quiet(true);
    while (!at(TokenKind::End) && !at(TokenKind::RBrace) &&
           !(at(TokenKind::Identifier) && (find_block_spec(peek().text) || is_statement_keyword(peek().text))))
        take();
    lexer_.set_quiet(false);
}

// Everything left, unreported: after nesting too deep to parse, the rest is a generated or
// broken file.
void Parser::skip_rest_of_file() {
    lexer_.set_quiet(true);
    while (!at(TokenKind::End)) take();
    lexer_.set_quiet(false);
    gave_up_ = true;  // the braces still open close with nothing more said
}

}  // namespace tracer
