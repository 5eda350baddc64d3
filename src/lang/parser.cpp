#include "lang/parser.h"

#include <deque>

#include "lang/lexer.h"
#include "lang/schema.h"

namespace tracer {
namespace {

// Thrown after a syntax error has been reported, to unwind to the top-level block.
struct SyntaxError {};
// Thrown when a new top-level block starts before the current one was closed.
struct UnclosedBlock {};

struct OpenBrace {
    Span span;
    std::string owner;  // what the brace opened, for "to close the 'sphere' block"
};

class Parser {
public:
    Parser(const SourceFile& file, Diagnostics& diagnostics)
        : file_(file), diagnostics_(diagnostics), lexer_(file, diagnostics) {}

    SceneAst parse_scene();
    bool parse_lone_value(Value& out);

private:
    // Token access with two tokens of look-ahead.
    const Token& peek(size_t ahead = 0);
    Token take();
    bool at(TokenKind kind, size_t ahead = 0) { return peek(ahead).kind == kind; }

    void parse_block(SceneAst& scene);
    void parse_body(Body& body, const std::string& owner);
    void parse_entry(Body& body);
    void parse_value(Value& value, const std::string& key);
    void parse_vector(Value& value);

    bool starts_new_block();
    [[noreturn]] void fail(const Token& token, std::string message);
    void skip_to_block_end();
    void skip_to_next_block();

    const SourceFile& file_;
    Diagnostics& diagnostics_;
    Lexer lexer_;
    std::deque<Token> lookahead_;
    std::vector<OpenBrace> open_;  // braces opened inside the current top-level block
};

const Token& Parser::peek(size_t ahead) {
    while (lookahead_.size() <= ahead) {
        lookahead_.push_back(lexer_.next());
    }
    return lookahead_[ahead];
}

Token Parser::take() {
    peek();
    Token token = std::move(lookahead_.front());
    lookahead_.pop_front();
    return token;
}

void Parser::fail(const Token& token, std::string message) {
    // The lexer has already reported an Error token: one message per mistake.
    if (token.kind != TokenKind::Error) diagnostics_.error(file_, token.span, std::move(message));
    throw SyntaxError{};
}

// scene = { block } ;
SceneAst Parser::parse_scene() {
    SceneAst scene;
    while (!at(TokenKind::End) && !diagnostics_.saturated()) {
        if (!at(TokenKind::Identifier)) {
            Token stray = take();
            if (stray.kind != TokenKind::Error)
                diagnostics_.error(file_, stray.span,
                               stray.kind == TokenKind::RBrace
                                   ? "unexpected '}': no block is open here"
                                   : "expected a block such as 'sphere { ... }', found " + describe(stray));
            skip_to_next_block();
            continue;
        }
        parse_block(scene);
    }
    return scene;
}

// block = identifier [ identifier ] body ;
void Parser::parse_block(SceneAst& scene) {
    Block block;
    Token kind = take();
    block.kind = std::string(kind.text);
    block.kind_span = kind.span;
    open_.clear();
    try {
        if (at(TokenKind::Identifier)) {
            Token name = take();
            block.name = std::string(name.text);
            block.name_span = name.span;
        }
        if (!at(TokenKind::LBrace))
            fail(peek(), "expected '{' after '" + std::string(kind.text) +
                             (block.name.empty() ? "" : " " + block.name) + "', found " + describe(peek()));
        parse_body(block.body, block.kind);
    } catch (const SyntaxError&) {
        block.broken = true;
        skip_to_block_end();
    } catch (const UnclosedBlock&) {
        block.broken = open_.size() > 1;  // entries so far are complete unless a nested block was cut
    }
    scene.blocks.push_back(std::move(block));
}

// body = "{" { entry } "}" ;
void Parser::parse_body(Body& body, const std::string& owner) {
    // Nesting goes three deep at most (`mesh { transform { rotate { } } }`); a deep pile of
    // braces is a mistake, and must not exhaust the stack of this recursive parser.
    constexpr size_t kMaxNesting = 16;
    if (open_.size() >= kMaxNesting) fail(peek(), "blocks are nested too deeply (more than 16 levels)");
    Token open = take();
    body.open_brace = open.span;
    open_.push_back({open.span, owner});
    while (!at(TokenKind::RBrace)) {
        if (at(TokenKind::End) || starts_new_block()) {
            const Token& next = peek();
            std::string where = at(TokenKind::End) ? "at end of file" : "before " + describe(next);
            Diagnostic* d = diagnostics_.error(file_, next.span, "expected '}' " + where);
            Diagnostics::note(d, file_, open_.back().span, "to close the '" + open_.back().owner + "' block opened here");
            throw UnclosedBlock{};
        }
        parse_entry(body);
    }
    body.close_brace = take().span;
    open_.pop_back();
}

// A top-level block written where a key was expected almost always means a missing '}':
// `sphere {`, `sphere name {` or `material name {` (a plain `material {` is an inline material).
bool Parser::starts_new_block() {
    if (!at(TokenKind::Identifier)) return false;
    std::string_view word = peek().text;
    if (!find_block_spec(word)) return false;
    if (word != "material" && at(TokenKind::LBrace, 1)) return true;
    return at(TokenKind::Identifier, 1) && at(TokenKind::LBrace, 2);
}

// entry = identifier value ;
void Parser::parse_entry(Body& body) {
    if (!at(TokenKind::Identifier))
        fail(peek(), "expected a key or '}', found " + describe(peek()));
    Entry entry;
    Token key = take();
    entry.key = std::string(key.text);
    entry.key_span = key.span;
    parse_value(entry.value, entry.key);
    body.entries.push_back(std::move(entry));
}

// value = number | vector | string | identifier | body ;
void Parser::parse_value(Value& value, const std::string& key) {
    const Token& token = peek();
    switch (token.kind) {
        case TokenKind::Number:
            value.kind = Value::Kind::Number;
            value.number = token.number;
            value.span = take().span;
            return;
        case TokenKind::String:
            value.kind = Value::Kind::String;
            value.span = token.span;
            value.text = take().string;
            return;
        case TokenKind::Identifier:
            value.kind = Value::Kind::Identifier;
            value.span = token.span;
            value.text = std::string(take().text);
            return;
        case TokenKind::LParen:
            parse_vector(value);
            return;
        case TokenKind::LBrace:
            value.kind = Value::Kind::Block;
            value.body = std::make_shared<Body>();
            value.span = token.span;
            parse_body(*value.body, key);
            value.span.end = value.body->close_brace.end;
            return;
        default:
            fail(token, "expected a value for '" + key + "', found " + describe(token));
    }
}

// vector = "(" number { "," number } ")" ;
void Parser::parse_vector(Value& value) {
    value.kind = Value::Kind::Vector;
    value.span = take().span;
    for (;;) {
        const Token& token = peek();
        if (token.kind != TokenKind::Number) {
            std::string found = describe(token);
            if (token.kind == TokenKind::Identifier)
                found += " (vector components are plain numbers; NaN and infinity are not allowed)";
            fail(token, "expected a number in vector, found " + found);
        }
        value.components.push_back(token.number);
        value.component_spans.push_back(take().span);
        if (at(TokenKind::Comma)) {
            take();
            continue;
        }
        if (at(TokenKind::RParen)) break;
        fail(peek(), "expected ',' or ')' in vector, found " + describe(peek()));
    }
    value.span.end = take().span.end;
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

// After a stray token at the top level: skip to something that can start a block.
void Parser::skip_to_next_block() {
    while (!at(TokenKind::End) && !at(TokenKind::Identifier)) take();
}

bool Parser::parse_lone_value(Value& out) {
    try {
        parse_value(out, "default");
    } catch (const SyntaxError&) {
        return false;
    } catch (const UnclosedBlock&) {
        return false;
    }
    return at(TokenKind::End);
}

}  // namespace

SceneAst parse_scene(const SourceFile& file, Diagnostics& diagnostics) {
    return Parser(file, diagnostics).parse_scene();
}

bool parse_single_value(const SourceFile& file, Diagnostics& diagnostics, Value& out) {
    return Parser(file, diagnostics).parse_lone_value(out);
}

}  // namespace tracer
