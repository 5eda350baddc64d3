// The parser's class, shared by its three files: parser.cpp (statements), parse_expressions.cpp
// (expressions) and parse_recovery.cpp (skipping past a syntax error). Internal to the parser.
#pragma once

#include <deque>
#include <string>
#include <vector>

#include "base/diagnostics.h"
#include "base/source.h"
#include "lang/internal/lexer.h"
#include "lang/internal/syntax_tree.h"

namespace tracer {

// Thrown after a syntax error has been reported, to unwind to the top-level block.
struct SyntaxError {};
// Thrown when a new top-level block starts before the current one was closed.
struct UnclosedBlock {};

struct OpenBrace {
    Span span;
    std::string owner;  // what the brace opened, for "to close the 'sphere' block"
};

// Nesting deeper than this (parentheses, unary minus, conditions, statements in braces) is
// refused: the parser recurses.
inline constexpr int kMaxParseDepth = 200;
// Most terms one chain of + - * / (or and, or or) may have, most values one list, vector or call
// may have, and most entries one block may have: the syntax tree of one statement is held
// whole, so its size is bounded where it is read (a scene repeats statements with loops).
inline constexpr size_t kMaxTerms = 100'000;
inline constexpr size_t kMaxEntries = 10'000;

// The words that start a statement other than a block.
bool is_statement_keyword(std::string_view word);
// The keys a group's placement is written with (before its contents).
bool is_placement_key(std::string_view word);
// POV-Ray's CSG block kinds (union, merge, intersection, difference), which tracer does not have.
// union, merge, intersection, difference: the blocks of solid modelling (CSG), statements like a group.
bool is_solid_keyword(std::string_view word);
// group, or a solid's keyword: a statement holding statements, its placement first.
bool is_group_keyword(std::string_view word);
// A block kind whose blocks put something in the scene (not material, render, camera), or a
// group's or solid's keyword: what a shape value may be (let NAME = sphere { ... }).
bool makes_things(std::string_view word);

class Parser {
public:
    Parser(const SourceFile& file, Diagnostics& diagnostics, uint32_t origin)
        : file_(file), diagnostics_(diagnostics), lexer_(file, diagnostics, origin) {}

    Program parse_program();
    bool next_statement(std::vector<Statement>& out);
    bool parse_lone_value(Expr& out);

private:
    // Token access with three tokens of look-ahead.
    const Token& peek(size_t ahead = 0);
    Token take();
    bool at(TokenKind kind, size_t ahead = 0) { return peek(ahead).kind == kind; }
    bool at_word(std::string_view word, size_t ahead = 0) {
        return at(TokenKind::Identifier, ahead) && peek(ahead).text == word;
    }

    // Statements (parser.cpp).
    void parse_statements(std::vector<Statement>& out, bool nested);
    void parse_statement(std::vector<Statement>& out);
    void parse_block(std::vector<Statement>& out);
    void parse_binding(std::vector<Statement>& out, Statement::Kind kind);
    template <class Parse>
    void parse_block_guarded(std::vector<Statement>& out, Statement block, Parse parse);
    // Runs `parse` on a statement that is not a block and keeps it; after a syntax error it is
    // dropped and the parser skips to the next statement.
    template <class Parse>
    void parse_guarded(std::vector<Statement>& out, Statement statement, Parse parse);
    void parse_loop(std::vector<Statement>& out);
    void parse_while(std::vector<Statement>& out);
    bool parse_condition(Statement& statement, Span& open_brace);
    void parse_assignment(std::vector<Statement>& out);
    void parse_if(std::vector<Statement>& out);
    void parse_function(std::vector<Statement>& out);
    void parse_return(std::vector<Statement>& out);
    void parse_call(std::vector<Statement>& out);
    // let NAME = a shape's, a light's, a group's or a solid's block: a shape value.
    void parse_shape_value(std::vector<Statement>& out);
    // A name alone on its line: the shape value it names, placed here.
    void parse_placed_value(std::vector<Statement>& out);
    void parse_group(std::vector<Statement>& out);
    void parse_include(std::vector<Statement>& out);
    // The statements of a body whose '{' (at `open_brace`, opened by `owner`) was just taken, and
    // its '}'; false if it was too deep to parse (reported, the rest of the file skipped).
    bool parse_braced_statements(Statement& statement, std::vector<Statement>& out, Span open_brace,
                                 const std::string& owner);
    void parse_body(BodyCode& body, const std::string& owner);
    void parse_entry(BodyCode& body);
    void parse_value(Expr& value, const std::string& key);

    // Expressions (parse_expressions.cpp).
    Expr parse_expression();
    Expr parse_and();
    Expr parse_chain(std::string_view word, Expr (Parser::*operand)());
    Expr parse_not();
    Expr parse_comparison();
    Expr parse_sum();
    Expr parse_term();
    Expr parse_unary();
    Expr parse_postfix();
    Expr parse_primary();
    Expr parse_conditional();
    void parse_list(Expr& value, TokenKind close, const char* what);
    void enter_nesting();
    // Fails at the next token if `count` terms, values or entries are already too many.
    void check_size(size_t count, size_t most, const char* what);
    // Reports `message` at `token`, skips the rest of the file and throws SyntaxError (nesting
    // this deep is a generated or broken file: what follows would only add errors).
    [[noreturn]] void fail_and_skip_file(const Token& token, const std::string& message);
    Token expect(TokenKind kind, const std::string& what);

    // Recovery (parse_recovery.cpp).
    bool starts_new_block();
    bool starts_statement();
    void skip_to_next_statement();
    void skip_broken_header(Span keyword);
    void skip_unknown_statement(const Token& word);
    void skip_rest_of_file();
    std::string range_call_hint(const Expr& call, const std::string& name) const;
    [[noreturn]] void fail(const Token& token, std::string message);
    void skip_to_block_end();

    const SourceFile& file_;
    Diagnostics& diagnostics_;
    Lexer lexer_;
    std::deque<Token> lookahead_;
    std::vector<OpenBrace> open_;  // braces opened inside the current block
    int depth_ = 0;                // expressions nested: a bound against stack overflow (so is nesting_)
    int nesting_ = 0;              // loops, conditions, functions and groups around the statement being parsed
    int functions_ = 0;            // functions around it ('return' is allowed)
    bool gave_up_ = false;         // the rest of the file was skipped after an error: no more reports
};

}  // namespace tracer
