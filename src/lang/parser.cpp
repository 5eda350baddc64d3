#include "lang/internal/parser.h"

#include "lang/internal/parser_class.h"
#include "lang/internal/suggest.h"
#include "lang/schema.h"

namespace tracer {

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

// scene = { statement } ;
Program Parser::parse_program() {
    Program program;
    parse_statements(program.statements, false);
    return program;
}

// The statements of the file, or of a body up to its '}' (`nested`).
void Parser::parse_statements(std::vector<Statement>& out, bool nested) {
    while (!at(TokenKind::End) && !diagnostics_.saturated()) {
        if (nested && at(TokenKind::RBrace)) return;
        next_statement(out);
    }
}

// One statement (appended to `out`, unless it was too broken to keep); false at the end of
// the file or once the errors are too many to go on.
bool Parser::next_statement(std::vector<Statement>& out) {
    if (at(TokenKind::End) || diagnostics_.saturated()) return false;
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
    return true;
}

// statement = block | let | shape value | param | for | if | function | return | call | placed value
//             | group | include ;
void Parser::parse_statement(std::vector<Statement>& out) {
    const std::string_view word = peek().text;
    if (word == "let" && at(TokenKind::Identifier, 1) && at(TokenKind::Equals, 2) && at(TokenKind::Identifier, 3) &&
        at(TokenKind::LBrace, 4) && makes_things(peek(3).text))
        return parse_shape_value(out);
    if (word == "let" && at(TokenKind::Identifier, 1)) return parse_binding(out, Statement::Kind::Let);
    if (word == "param" && at(TokenKind::Identifier, 1)) return parse_binding(out, Statement::Kind::Param);
    if (word == "for" && at(TokenKind::Identifier, 1)) return parse_loop(out);
    if (word == "while") return parse_while(out);
    if (!is_statement_keyword(word) && at(TokenKind::Equals, 1)) return parse_assignment(out);
    if (word == "include" && at(TokenKind::String, 1)) return parse_include(out);
    if (word == "fn" && at(TokenKind::Identifier, 1)) return parse_function(out);
    if (word == "if") return parse_if(out);
    if (word == "return") return parse_return(out);
    if (is_group_keyword(word) && at(TokenKind::LBrace, 1)) return parse_group(out);
    if (!is_statement_keyword(word) && at(TokenKind::LParen, 1)) return parse_call(out);
    if (!is_statement_keyword(word) && !find_block_spec(word) && povray_hint(word).empty() &&
        !at(TokenKind::LBrace, 1) &&
        (at(TokenKind::End, 1) || at(TokenKind::RBrace, 1) ||
         file_.locate(peek(1).span.begin).line != file_.locate(peek().span.begin).line))
        return parse_placed_value(out);
    if (is_statement_keyword(word)) {  // a statement whose name (or path) is missing or broken
        const Span keyword = take().span;
        if (!at(TokenKind::Error))  // else the lexer has said what is wrong with it
            diagnostics_.error(file_, peek().span,
                               std::string("expected ") +
                                   (word == "include"        ? "a file path in quotes"
                                    : is_group_keyword(word) ? "'{'"
                                                             : "a name") +
                                   " after '" + std::string(word) + "', found " + describe(peek()));
        if (word == "for" || word == "fn" || is_group_keyword(word)) return skip_broken_header(keyword);
        // The offending word is part of this statement, not the start of the next.
        if (!at(TokenKind::End) && !at(TokenKind::RBrace) &&
            file_.locate(peek().span.begin).line == file_.locate(keyword.begin).line)
            take();
        skip_to_next_statement();
        return;
    }
    parse_block(out);
}

// assignment = identifier "=" expression ;
void Parser::parse_assignment(std::vector<Statement>& out) {
    Statement statement;
    statement.kind = Statement::Kind::Assign;
    const Token name = take();
    statement.keyword = name.span;
    statement.name = std::string(name.text);
    statement.name_span = name.span;
    parse_guarded(out, std::move(statement), [&](Statement& assignment) {
        take();  // '='
        assignment.value = parse_expression();
    });
}

// while = "while" expression "{" { statement } "}" ;
void Parser::parse_while(std::vector<Statement>& out) {
    Statement loop;
    loop.kind = Statement::Kind::While;
    loop.keyword = take().span;
    Span open_brace;
    if (!parse_condition(loop, open_brace)) return;
    if (parse_braced_statements(loop, loop.statements, open_brace, "'while' loop")) out.push_back(std::move(loop));
}

// The condition of an if or a while and the '{' after it (`open_brace`); false after a syntax
// error (reported, and the header skipped).
bool Parser::parse_condition(Statement& statement, Span& open_brace) {
    open_.clear();
    try {
        statement.value = parse_expression();
        if (at(TokenKind::Equals)) fail(peek(), "'=' gives a name its value; to compare two values write '=='");
        open_brace = expect(TokenKind::LBrace, "'{' after the condition").span;
    } catch (const SyntaxError&) {
        skip_broken_header(statement.keyword);
        return false;
    } catch (const UnclosedBlock&) {
        return false;
    }
    return true;
}

// let = "let" identifier "=" expression ;   param = "param" identifier "=" expression ;
void Parser::parse_binding(std::vector<Statement>& out, Statement::Kind kind) {
    Statement statement;
    statement.kind = kind;
    statement.keyword = take().span;
    Token name = take();
    statement.name = std::string(name.text);
    statement.name_span = name.span;
    parse_guarded(out, std::move(statement), [&](Statement& binding) {
        if (kind == Statement::Kind::Param && nesting_ > 0) {
            diagnostics_.error(file_, binding.keyword,
                               "a 'param' is declared at the top level of a file, not inside braces");
            throw SyntaxError{};
        }
        expect(TokenKind::Equals, "'=' after '" + binding.name + "'");
        binding.value = parse_expression();
    });
}

template <class Parse>
void Parser::parse_guarded(std::vector<Statement>& out, Statement statement, Parse parse) {
    open_.clear();
    try {
        parse(statement);
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

bool Parser::parse_braced_statements(Statement& statement, std::vector<Statement>& out, Span open_brace,
                                     const std::string& owner) {
    if (nesting_ + 1 > kMaxParseDepth) {
        diagnostics_.error(file_, statement.keyword, "statements are nested too deeply (more than 200 levels)");
        skip_rest_of_file();
        return false;
    }
    ++nesting_;
    parse_statements(out, true);
    --nesting_;
    if (at(TokenKind::End)) {
        statement.broken = true;  // cut short: a solid's missing parts are not news
        if (!gave_up_) {
            Diagnostic* d = diagnostics_.error(file_, peek().span, "expected '}' at end of file");
            Diagnostics::note(d, file_, open_brace, "to close the " + owner + " opened here");
        }
    } else {
        statement.end_brace = take().span;  // '}'
    }
    return true;
}

// for = "for" identifier "in" ( expression ".." expression | expression ) "{" { statement } "}" ;
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
        if (!at_word("in"))
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
        if (at(TokenKind::LBrace)) {
            loop.over_list = true;
        } else {
            expect(TokenKind::DotDot, "'..' between the first and the end of the range, or '{' after a list");
            if (at(TokenKind::Equals))
                fail(peek(), "'..=' is not a range: A..B already stops before B; to include B write A..B + 1");
            loop.end = parse_expression();
        }
        open_brace = expect(TokenKind::LBrace, "'{' to open the loop's body").span;
    } catch (const SyntaxError&) {
        skip_broken_header(loop.keyword);
        return;
    } catch (const UnclosedBlock&) {
        return;
    }
    if (parse_braced_statements(loop, loop.statements, open_brace, "'for' loop")) out.push_back(std::move(loop));
}

// if = "if" expression "{" { statement } "}" [ "else" ( "{" { statement } "}" | if ) ] ;
void Parser::parse_if(std::vector<Statement>& out) {
    Statement condition;
    condition.kind = Statement::Kind::If;
    condition.keyword = take().span;
    Span open_brace;
    if (!parse_condition(condition, open_brace)) return;
    if (!parse_braced_statements(condition, condition.statements, open_brace, "'if' body")) return;
    if (at_word("else")) {
        const Token word = take();
        if (at_word("if")) {
            // else if: an If statement alone in the else branch (nested one level per 'else if').
            if (nesting_ + 1 > kMaxParseDepth) {
                diagnostics_.error(file_, word.span, "statements are nested too deeply (more than 200 levels)");
                skip_rest_of_file();
                return;
            }
            ++nesting_;
            parse_if(condition.otherwise);
            --nesting_;
        } else if (at(TokenKind::LBrace)) {
            const Span brace = take().span;
            Statement branch;
            branch.keyword = word.span;
            if (!parse_braced_statements(branch, condition.otherwise, brace, "'else' body")) return;
            condition.end_brace = branch.end_brace;
        } else {
            diagnostics_.error(file_, peek().span, "expected '{' or 'if' after 'else', found " + describe(peek()));
            skip_to_next_statement();
        }
    }
    out.push_back(std::move(condition));
}

// function = "fn" identifier "(" [ identifier { "," identifier } ] ")" "{" { statement } "}" ;
void Parser::parse_function(std::vector<Statement>& out) {
    Statement function;
    function.kind = Statement::Kind::Function;
    function.keyword = take().span;
    Token name = take();
    function.name = std::string(name.text);
    function.name_span = name.span;
    open_.clear();
    Span open_brace;
    try {
        expect(TokenKind::LParen, "'(' and the parameters after 'fn " + function.name + "'");
        while (!at(TokenKind::RParen)) {
            const Token parameter = expect(TokenKind::Identifier, "a parameter's name");
            function.parameters.emplace_back(std::string(parameter.text), parameter.span);
            if (!at(TokenKind::RParen)) expect(TokenKind::Comma, "',' or ')' after a parameter");
        }
        take();
        open_brace = expect(TokenKind::LBrace, "'{' to open the function's body").span;
    } catch (const SyntaxError&) {
        skip_broken_header(function.keyword);
        return;
    }
    ++functions_;
    const bool parsed = parse_braced_statements(function, function.statements, open_brace, "function 'fn'");
    --functions_;
    if (parsed) out.push_back(std::move(function));
}

// return = "return" [ expression ] ;   (a value only on the keyword's own line)
void Parser::parse_return(std::vector<Statement>& out) {
    Statement statement;
    statement.kind = Statement::Kind::Return;
    statement.keyword = take().span;
    parse_guarded(out, std::move(statement), [&](Statement& done) {
        if (functions_ == 0) {
            diagnostics_.error(file_, done.keyword, "'return' is written inside a function's body (fn)");
            throw SyntaxError{};
        }
        done.has_value = !at(TokenKind::End) && !at(TokenKind::RBrace) &&
                         file_.locate(peek().span.begin).line == file_.locate(done.keyword.begin).line;
        if (done.has_value) done.value = parse_expression();
    });
}

// call = identifier "(" [ expression { "," expression } ] ")" ;   (a function making blocks)
void Parser::parse_call(std::vector<Statement>& out) {
    Statement call;
    call.kind = Statement::Kind::Call;
    call.keyword = peek().span;
    parse_guarded(out, std::move(call), [&](Statement& statement) {
        statement.value = parse_postfix();
        if (statement.value.kind != Expr::Kind::Call)
            fail(peek(), "expected a block or a statement; a value alone does nothing, found " + describe(peek()));
    });
}

// shape value = "let" identifier "=" ( group | block ) ;   (a block that makes things: a shape, a
// light, a group or a solid, made where its name is placed, from the names as they were here)
void Parser::parse_shape_value(std::vector<Statement>& out) {
    Statement function;
    function.kind = Statement::Kind::Function;
    function.shape_value = true;
    function.keyword = take().span;
    const Token name = take();
    function.name = std::string(name.text);
    function.name_span = name.span;
    take();  // '='
    parse_statement(function.statements);
    out.push_back(std::move(function));
}

// placed value = identifier ;   (alone on its line)
void Parser::parse_placed_value(std::vector<Statement>& out) {
    Statement call;
    call.kind = Statement::Kind::Call;
    call.shape_value = true;
    const Token name = take();
    call.keyword = name.span;
    call.value.kind = Expr::Kind::Call;
    call.value.text = std::string(name.text);
    call.value.span = name.span;
    out.push_back(std::move(call));
}

// group = ( "group" | solid ) "{" { placement } { statement } "}" ;   placement = ( "scale" |
// "rotate" | "translate" | "transform" ) value ;   solid = "union" | "merge" | "intersection" |
// "difference" ;
void Parser::parse_group(std::vector<Statement>& out) {
    Statement group;
    group.kind = Statement::Kind::Group;
    const Token keyword = take();
    group.keyword = keyword.span;
    group.word = std::string(keyword.text);
    const Span open_brace = take().span;
    group.body.open_brace = open_brace;
    open_.clear();
    while (at(TokenKind::Identifier) && is_placement_key(peek().text)) {
        open_.clear();
        open_.push_back({open_brace, group.word});
        try {
            parse_entry(group.body);
        } catch (const SyntaxError&) {
            skip_to_next_statement();
        } catch (const UnclosedBlock&) {
        }
    }
    open_.clear();
    if (!parse_braced_statements(group, group.statements, open_brace, "'" + group.word + "' block")) return;
    group.body.close_brace = group.end_brace;
    out.push_back(std::move(group));
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
    // A word that is no block, with no body after it (`scael 2`): one message, not "expected
    // '{'" and then "unknown block" for the same word.
    if (!find_block_spec(kind.text) && !at(TokenKind::LBrace) &&
        !(at(TokenKind::Identifier) && at(TokenKind::LBrace, 1)))
        return skip_unknown_statement(kind);
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
        check_size(body.entries.size(), kMaxEntries, "entries");
        parse_entry(body);
    }
    body.close_brace = take().span;
    open_.pop_back();
}

// entry = identifier value ;
void Parser::parse_entry(BodyCode& body) {
    if (!at(TokenKind::Identifier)) {
        // Inside POV-Ray's `pigment { checker ..., ... }`: its hint says what tracer writes instead.
        const std::string owner_hint = open_.empty() ? "" : povray_hint(open_.back().owner);
        fail(peek(),
             "expected a key or '}', found " + describe(peek()) +
                 (!owner_hint.empty()   ? owner_hint + " (inside '" + open_.back().owner + "')"
                  : at(TokenKind::Less) ? "; each value is named by its key here, and a vector is (x, y, z): "
                                          "sphere { center (0, 0, 0) radius 1 ... }, not sphere { <0, 0, 0>, 1 }"
                                        : ""));
    }
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
        kind != TokenKind::LParen && kind != TokenKind::Minus && kind != TokenKind::Plus &&
        kind != TokenKind::LBracket && kind != TokenKind::Less)
        fail(peek(), "expected a value for '" + key + "', found " + describe(peek()));
    value = parse_expression();
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
