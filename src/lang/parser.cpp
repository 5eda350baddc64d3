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

// The words that start a statement other than a block.
bool is_statement_keyword(std::string_view word) {
    return word == "let" || word == "param" || word == "for" || word == "include";
}

}  // namespace

class Parser {
public:
    Parser(const SourceFile& file, Diagnostics& diagnostics, uint32_t origin)
        : file_(file), diagnostics_(diagnostics), lexer_(file, diagnostics, origin) {}

    Program parse_program();
    bool next_statement(std::vector<Statement>& out);
    bool parse_lone_value(Expr& out);

private:
    // Token access with two tokens of look-ahead.
    const Token& peek(size_t ahead = 0);
    Token take();
    bool at(TokenKind kind, size_t ahead = 0) { return peek(ahead).kind == kind; }

    void parse_statements(std::vector<Statement>& out, bool in_loop);
    void parse_statement(std::vector<Statement>& out);
    void parse_block(std::vector<Statement>& out);
    void parse_binding(std::vector<Statement>& out, Statement::Kind kind);
    void parse_named_material(std::vector<Statement>& out, const Statement& let);
    template <class Parse>
    void parse_block_guarded(std::vector<Statement>& out, Statement block, Parse parse);
    void parse_loop(std::vector<Statement>& out);
    void parse_include(std::vector<Statement>& out);
    void parse_body(BodyCode& body, const std::string& owner);
    void parse_entry(BodyCode& body);
    void parse_value(Expr& value, const std::string& key);
    Expr parse_expression();
    Expr parse_term();
    Expr parse_unary();
    Expr parse_postfix();
    Expr parse_primary();
    Token expect(TokenKind kind, const std::string& what);

    bool starts_new_block();
    bool starts_statement();
    void skip_to_next_statement();
    void skip_broken_loop(Span keyword);
    std::string range_call_hint(const Expr& call, const std::string& name) const;
    [[noreturn]] void fail(const Token& token, std::string message);
    void skip_to_block_end();

    const SourceFile& file_;
    Diagnostics& diagnostics_;
    Lexer lexer_;
    std::deque<Token> lookahead_;
    std::vector<OpenBrace> open_;  // braces opened inside the current block
    int depth_ = 0;                // expressions nested: a bound against stack overflow (so is loops_)
    int loops_ = 0;                // loops around the statement being parsed
};

// Nesting deeper than this (parentheses, unary minus, loops) is refused: the parser recurses.
static constexpr int kMaxDepth = 200;

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

// scene = { statement } ;
Program Parser::parse_program() {
    Program program;
    parse_statements(program.statements, false);
    return program;
}

// The statements of the file, or of a loop's body up to its '}'.
void Parser::parse_statements(std::vector<Statement>& out, bool in_loop) {
    while (!at(TokenKind::End) && !diagnostics_.saturated()) {
        if (in_loop && at(TokenKind::RBrace)) return;
        next_statement(out);
    }
}

// One statement (appended to `out`, unless it was too broken to keep); false at the end of
// the file or once the errors are too many to go on.
bool Parser::next_statement(std::vector<Statement>& out) {
    if (at(TokenKind::End) || diagnostics_.saturated()) return false;
    {
        if (!at(TokenKind::Identifier)) {
            Token stray = take();
            if (stray.kind != TokenKind::Error)
                diagnostics_.error(file_, stray.span,
                                   stray.kind == TokenKind::RBrace
                                       ? "unexpected '}': no block is open here"
                                       : "expected a block such as 'sphere { ... }', found " + describe(stray));
            skip_to_next_statement();
            return true;
        }
        parse_statement(out);
    }
    return true;
}

// statement = block | let | param | for | include ;
void Parser::parse_statement(std::vector<Statement>& out) {
    const std::string_view word = peek().text;
    if (word == "let" && at(TokenKind::Identifier, 1)) return parse_binding(out, Statement::Kind::Let);
    if (word == "param" && at(TokenKind::Identifier, 1)) return parse_binding(out, Statement::Kind::Param);
    if (word == "for" && at(TokenKind::Identifier, 1)) return parse_loop(out);
    if (word == "include" && at(TokenKind::String, 1)) return parse_include(out);
    if (is_statement_keyword(word)) {  // a statement whose name (or path) is missing or broken
        const bool loop = word == "for";
        const Span keyword = take().span;
        if (!at(TokenKind::Error))  // else the lexer has said what is wrong with it
            diagnostics_.error(file_, peek().span,
                               std::string("expected ") + (word == "include" ? "a file path in quotes" : "a name") +
                                   " after '" + std::string(word) + "', found " + describe(peek()));
        if (loop) return skip_broken_loop(keyword);
        // The offending word is part of this statement, not the start of the next.
        if (!at(TokenKind::End) && !at(TokenKind::RBrace) &&
            file_.locate(peek().span.begin).line == file_.locate(keyword.begin).line)
            take();
        skip_to_next_statement();
        return;
    }
    parse_block(out);
}

// let = "let" identifier "=" expression ;   param = "param" identifier "=" expression ;
void Parser::parse_binding(std::vector<Statement>& out, Statement::Kind kind) {
    Statement statement;
    statement.kind = kind;
    statement.keyword = take().span;
    Token name = take();
    statement.name = std::string(name.text);
    statement.name_span = name.span;
    open_.clear();
    try {
        if (kind == Statement::Kind::Param && loops_ > 0) {
            diagnostics_.error(file_, statement.keyword,
                               "a 'param' is declared at the top level of a file, not inside a loop");
            throw SyntaxError{};
        }
        expect(TokenKind::Equals, "'=' after '" + statement.name + "'");
        if (kind == Statement::Kind::Let && at(TokenKind::Identifier) && peek().text == "material" &&
            at(TokenKind::LBrace, 1))
            return parse_named_material(out, statement);
        statement.value = parse_expression();
    } catch (const SyntaxError&) {
        skip_to_next_statement();
        return;
    } catch (const UnclosedBlock&) {
        return;
    }
    out.push_back(std::move(statement));
}

// Runs `parse` on a block's statement and keeps the block: after a syntax error it is marked
// broken (reported once, not validated) and the parser skips to the block's end.
template <class Parse>
void Parser::parse_block_guarded(std::vector<Statement>& out, Statement block, Parse parse) {
    try {
        parse(block);
    } catch (const SyntaxError&) {
        block.broken = true;
        skip_to_block_end();
    } catch (const UnclosedBlock&) {
        block.broken = open_.size() > 1;  // entries so far are complete unless a nested block was cut
    }
    out.push_back(std::move(block));
}

// `let gold = material { ... }` is another way to write `material gold { ... }`.
void Parser::parse_named_material(std::vector<Statement>& out, const Statement& let) {
    Statement block;
    block.word = "material";
    block.keyword = take().span;
    block.name = let.name;
    block.name_span = let.name_span;
    parse_block_guarded(out, std::move(block), [&](Statement& material) { parse_body(material.body, material.word); });
}

// for = "for" identifier "in" expression ".." expression "{" { statement } "}" ;
void Parser::parse_loop(std::vector<Statement>& out) {
    Statement loop;
    loop.kind = Statement::Kind::For;
    loop.keyword = take().span;
    Token name = take();
    loop.name = std::string(name.text);
    loop.name_span = name.span;
    open_.clear();
    Span open_brace;
    try {
        if (!(at(TokenKind::Identifier) && peek().text == "in"))
            fail(peek(),
                 "expected 'in' after 'for " + loop.name + "', found " + describe(peek()) +
                     (at(TokenKind::Equals) ? "; a loop is written 'for " + loop.name + " in A..B' (from A up to B - 1)"
                                            : ""));
        take();
        loop.value = parse_expression();
        if (!at(TokenKind::DotDot) && loop.value.kind == Expr::Kind::Call && loop.value.text == "range") {
            diagnostics_.error(file_, loop.value.span, range_call_hint(loop.value, loop.name));
            throw SyntaxError{};
        }
        expect(TokenKind::DotDot, "'..' between the first and the end of the range");
        if (at(TokenKind::Equals))
            fail(peek(), "'..=' is not a range: A..B already stops before B; to include B write A..B + 1");
        loop.end = parse_expression();
        open_brace = expect(TokenKind::LBrace, "'{' to open the loop's body").span;
    } catch (const SyntaxError&) {
        skip_broken_loop(loop.keyword);
        return;
    } catch (const UnclosedBlock&) {
        return;
    }
    if (loops_ + 1 > kMaxDepth) {
        // Deeper is a generated or broken file: report once and skip the rest of it.
        diagnostics_.error(file_, loop.keyword, "loops are nested too deeply (more than 200 levels)");
        lexer_.set_quiet(true);
        while (!at(TokenKind::End)) take();
        lexer_.set_quiet(false);
        return;
    }
    ++loops_;
    parse_statements(loop.statements, true);
    --loops_;
    if (at(TokenKind::End)) {
        Diagnostic* d = diagnostics_.error(file_, peek().span, "expected '}' at end of file");
        Diagnostics::note(d, file_, open_brace, "to close the 'for' loop opened here");
    } else {
        take();  // '}'
    }
    out.push_back(std::move(loop));
}

// include = "include" string ;
void Parser::parse_include(std::vector<Statement>& out) {
    Statement include;
    include.kind = Statement::Kind::Include;
    include.keyword = take().span;
    Token path = take();
    include.word = path.string;
    include.name_span = path.span;
    out.push_back(std::move(include));
}

// block = identifier [ identifier ] body ;
void Parser::parse_block(std::vector<Statement>& out) {
    Statement block;
    Token kind = take();
    block.word = std::string(kind.text);
    block.keyword = kind.span;
    open_.clear();
    parse_block_guarded(out, std::move(block), [&](Statement& statement) {
        if (at(TokenKind::Identifier)) {
            Token name = take();
            statement.name = std::string(name.text);
            statement.name_span = name.span;
        }
        if (!at(TokenKind::LBrace)) {
            std::string message = "expected '{' after '" + std::string(kind.text) +
                                  (statement.name.empty() ? "" : " " + statement.name) + "', found " + describe(peek());
            if (at(TokenKind::Equals))  // POV-Ray's `#declare R = 0.5;` without the '#'
                message += "; a name is given a value by 'let NAME = value'";
            fail(peek(), message);
        }
        parse_body(statement.body, statement.word);
    });
}

// body = "{" { entry } "}" ;
void Parser::parse_body(BodyCode& body, const std::string& owner) {
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
            Diagnostics::note(d, file_, open_.back().span,
                              "to close the '" + open_.back().owner + "' block opened here");
            throw UnclosedBlock{};
        }
        parse_entry(body);
    }
    body.close_brace = take().span;
    open_.pop_back();
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

// `let x =`, `param x =`, `for x in`, `include "..."`.
bool Parser::starts_statement() {
    if (!at(TokenKind::Identifier)) return false;
    std::string_view word = peek().text;
    if ((word == "let" || word == "param") && at(TokenKind::Identifier, 1) && at(TokenKind::Equals, 2)) return true;
    if (word == "for" && at(TokenKind::Identifier, 1) && at(TokenKind::Identifier, 2) && peek(2).text == "in")
        return true;
    return word == "include" && at(TokenKind::String, 1);
}

Token Parser::expect(TokenKind kind, const std::string& what) {
    if (!at(kind)) fail(peek(), "expected " + what + ", found " + describe(peek()));
    return take();
}

// entry = identifier value ;
void Parser::parse_entry(BodyCode& body) {
    if (!at(TokenKind::Identifier)) fail(peek(), "expected a key or '}', found " + describe(peek()));
    EntryCode entry;
    Token key = take();
    entry.key = std::string(key.text);
    entry.key_span = key.span;
    if (at(TokenKind::Equals)) fail(peek(), "a key takes its value without '=': write '" + entry.key + " value'");
    parse_value(entry.value, entry.key);
    body.entries.push_back(std::move(entry));
}

// value = expression | body ;
void Parser::parse_value(Expr& value, const std::string& key) {
    if (at(TokenKind::LBrace)) {
        value.kind = Expr::Kind::Block;
        value.body = std::make_shared<BodyCode>();
        value.span = peek().span;
        parse_body(*value.body, key);
        value.span.end = value.body->close_brace.end;
        return;
    }
    const TokenKind kind = peek().kind;
    if (kind != TokenKind::Number && kind != TokenKind::String && kind != TokenKind::Identifier &&
        kind != TokenKind::LParen && kind != TokenKind::Minus && kind != TokenKind::Plus)
        fail(peek(), "expected a value for '" + key + "', found " + describe(peek()));
    value = parse_expression();
}

// `left op right`, spanning both.
static Expr binary_expression(Expr left, char op, Expr right) {
    Expr binary;
    binary.kind = Expr::Kind::Binary;
    binary.op = op;
    binary.span = {left.span.begin, right.span.end, left.span.origin};
    binary.operands.push_back(std::move(left));
    binary.operands.push_back(std::move(right));
    return binary;
}

// expression = term { ( "+" | "-" ) term } ;
Expr Parser::parse_expression() {
    Expr left = parse_term();
    while (at(TokenKind::Plus) || at(TokenKind::Minus)) {
        const char op = take().kind == TokenKind::Plus ? '+' : '-';
        left = binary_expression(std::move(left), op, parse_term());
    }
    return left;
}

// term = unary { ( "*" | "/" ) unary } ;
Expr Parser::parse_term() {
    Expr left = parse_unary();
    while (at(TokenKind::Star) || at(TokenKind::Slash)) {
        const char op = take().kind == TokenKind::Star ? '*' : '/';
        left = binary_expression(std::move(left), op, parse_unary());
    }
    return left;
}

// unary = ( "-" | "+" ) unary | postfix ;
Expr Parser::parse_unary() {
    if (!at(TokenKind::Minus) && !at(TokenKind::Plus)) return parse_postfix();
    if (++depth_ > kMaxDepth) fail(peek(), "the expression is nested too deeply (more than 200 levels)");
    Expr unary;
    unary.kind = Expr::Kind::Unary;
    const Token sign = take();
    unary.op = sign.kind == TokenKind::Minus ? '-' : '+';
    unary.operands.push_back(parse_unary());
    unary.span = {sign.span.begin, unary.operands[0].span.end, sign.span.origin};
    --depth_;
    return unary;
}

// postfix = primary { "." identifier } ;
Expr Parser::parse_postfix() {
    Expr value = parse_primary();
    for (int components = 0; at(TokenKind::Dot); ++components) {
        // A component of a number is an error: a long chain is a broken or hostile file.
        if (components == kMaxDepth) fail(peek(), "the expression is nested too deeply (more than 200 levels)");
        take();
        Token component = expect(TokenKind::Identifier, "a component name (x, y or z) after '.'");
        Expr access;
        access.kind = Expr::Kind::Component;
        access.text = std::string(component.text);
        access.span = {value.span.begin, component.span.end, value.span.origin};
        access.operands.push_back(std::move(value));
        value = std::move(access);
    }
    return value;
}

// primary = number | string | identifier [ "(" [ expression { "," expression } ] ")" ]
//         | "(" expression { "," expression } ")" ;
Expr Parser::parse_primary() {
    Expr value;
    const Token& token = peek();
    value.span = token.span;
    switch (token.kind) {
        case TokenKind::Number:
            value.kind = Expr::Kind::Number;
            value.number = take().number;
            return value;
        case TokenKind::String:
            value.kind = Expr::Kind::String;
            value.text = take().string;
            return value;
        case TokenKind::Identifier:
            value.kind = Expr::Kind::Name;
            value.text = std::string(take().text);
            if (!at(TokenKind::LParen)) return value;
            value.kind = Expr::Kind::Call;
            break;
        case TokenKind::LParen: value.kind = Expr::Kind::Vector; break;
        default:
            if (token.kind == TokenKind::Star && token.span.begin > 0 && file_.text()[token.span.begin - 1] == '*')
                fail(token, "'**' is not an operator; for a to the power b write pow(a, b)");
            fail(token, "expected a value, found " + describe(token));
    }
    // The parenthesised list of a call or a vector.
    if (++depth_ > kMaxDepth) fail(peek(), "the expression is nested too deeply (more than 200 levels)");
    take();  // '('
    const bool call = value.kind == Expr::Kind::Call;
    if (!(call && at(TokenKind::RParen))) {
        for (;;) {
            value.operands.push_back(parse_expression());
            if (at(TokenKind::Comma)) {
                take();
                continue;
            }
            if (at(TokenKind::RParen)) break;
            fail(peek(), std::string("expected ',' or ')' in ") + (call ? "the call" : "vector") + ", found " +
                             describe(peek()));
        }
    }
    value.span.end = take().span.end;
    --depth_;
    // (a) is a, in parentheses; (a, b, ...) a vector.
    if (!call && value.operands.size() == 1) {
        Expr inner = std::move(value.operands[0]);
        inner.span = value.span;
        return inner;
    }
    return value;
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

bool Parser::parse_lone_value(Expr& out) {
    try {
        parse_value(out, "default");
    } catch (const SyntaxError&) {
        return false;
    } catch (const UnclosedBlock&) {
        return false;
    }
    return at(TokenKind::End);
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

// After an error in a loop's header: skip the loop, body and all, when its '{' is on the
// keyword's line (so that the body's statements and '}' raise no errors of their own); else
// as after any broken statement.
void Parser::skip_broken_loop(Span keyword) {
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
}

// After a broken statement: skip to what can start the next one (a statement keyword, a block
// kind, or a loop's closing brace).
void Parser::skip_to_next_statement() {
    lexer_.set_quiet(true);
    while (!at(TokenKind::End) && !at(TokenKind::RBrace) &&
           !(at(TokenKind::Identifier) && (find_block_spec(peek().text) || is_statement_keyword(peek().text))))
        take();
    lexer_.set_quiet(false);
}

Program parse_program(const SourceFile& file, Diagnostics& diagnostics, uint32_t origin) {
    return Parser(file, diagnostics, origin).parse_program();
}

StatementReader::StatementReader(const SourceFile& file, Diagnostics& diagnostics, uint32_t origin)
    : parser_(std::make_unique<Parser>(file, diagnostics, origin)) {}
StatementReader::~StatementReader() = default;
bool StatementReader::next(std::vector<Statement>& out) {
    return parser_->next_statement(out);
}

bool parse_single_expression(const SourceFile& file, Diagnostics& diagnostics, Expr& out) {
    return Parser(file, diagnostics, 0).parse_lone_value(out);
}

}  // namespace tracer
