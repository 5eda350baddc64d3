// The parser's expression rules, lowest precedence first (grammar/scene.ebnf): or, and, not,
// comparisons, + -, * /, signs, components and indexes, and the primaries.
#include "lang/internal/parser_class.h"
#include "lang/schema.h"

namespace tracer {

namespace {

// `left op right`, spanning both.
Expr binary_expression(Expr::Kind kind, Expr left, char op, std::string text, Expr right) {
    Expr binary;
    binary.kind = kind;
    binary.op = op;
    binary.text = std::move(text);
    binary.span = {left.span.begin, right.span.end, left.span.origin};
    binary.operands.push_back(std::move(left));
    binary.operands.push_back(std::move(right));
    return binary;
}

const char* comparison_text(TokenKind kind) {
    switch (kind) {
        case TokenKind::EqualsEquals: return "==";
        case TokenKind::NotEquals: return "!=";
        case TokenKind::Less: return "<";
        case TokenKind::LessEquals: return "<=";
        case TokenKind::Greater: return ">";
        case TokenKind::GreaterEquals: return ">=";
        default: return nullptr;
    }
}

}  // namespace

void Parser::enter_nesting() {
    if (++depth_ > kMaxParseDepth)
        fail_and_skip_file(peek(), "the expression is nested too deeply (more than 200 levels)");
}

void Parser::check_size(size_t count, size_t most, const char* what) {
    if (count < most) return;
    fail_and_skip_file(peek(), "more than " + std::to_string(most) + " " + what +
                                   " in one statement (the limit); build large scenes with loops and functions");
}

void Parser::fail_and_skip_file(const Token& token, const std::string& message) {
    if (token.kind != TokenKind::Error) diagnostics_.error(file_, token.span, message);
    skip_rest_of_file();
    gave_up_ = true;
    throw SyntaxError{};
}

Token Parser::expect(TokenKind kind, const std::string& what) {
    if (!at(kind)) fail(peek(), "expected " + what + ", found " + describe(peek()));
    return take();
}

// expression = and { "or" and } ;   and = not { "and" not } ;   (kept flat: a chain of a
// million terms is one node, not a million levels)
Expr Parser::parse_expression() {
    return parse_chain("or", &Parser::parse_and);
}

Expr Parser::parse_and() {
    return parse_chain("and", &Parser::parse_not);
}

// operand { word operand }, one Logical node if the word occurs.
Expr Parser::parse_chain(std::string_view word, Expr (Parser::*operand)()) {
    Expr first = (this->*operand)();
    if (!at_word(word)) return first;
    Expr chain;
    chain.kind = Expr::Kind::Logical;
    chain.text = std::string(word);
    chain.span = first.span;
    chain.operands.push_back(std::move(first));
    while (at_word(word)) {
        check_size(chain.operands.size(), kMaxTerms, "terms");
        take();
        chain.operands.push_back((this->*operand)());
        chain.span.end = chain.operands.back().span.end;
    }
    return chain;
}

// not = "not" not | comparison ;
Expr Parser::parse_not() {
    if (!at_word("not")) return parse_comparison();
    const Token word = take();
    enter_nesting();
    Expr negation;
    negation.kind = Expr::Kind::Not;
    negation.operands.push_back(parse_not());
    negation.span = {word.span.begin, negation.operands[0].span.end, word.span.origin};
    --depth_;
    return negation;
}

// comparison = sum [ ( "==" | "!=" | "<" | "<=" | ">" | ">=" ) sum ] ;
Expr Parser::parse_comparison() {
    Expr left = parse_sum();
    const char* text = comparison_text(peek().kind);
    if (!text) return left;
    take();
    Expr comparison = binary_expression(Expr::Kind::Compare, std::move(left), 0, text, parse_sum());
    if (comparison_text(peek().kind)) fail(peek(), "comparisons do not chain: write 'a < b and b < c'");
    return comparison;
}

// sum = term { ( "+" | "-" ) term } ;
Expr Parser::parse_sum() {
    Expr left = parse_term();
    for (size_t terms = 1; at(TokenKind::Plus) || at(TokenKind::Minus); ++terms) {
        check_size(terms, kMaxTerms, "terms");
        const char op = take().kind == TokenKind::Plus ? '+' : '-';
        left = binary_expression(Expr::Kind::Binary, std::move(left), op, "", parse_term());
    }
    return left;
}

// term = unary { ( "*" | "/" ) unary } ;
Expr Parser::parse_term() {
    Expr left = parse_unary();
    for (size_t terms = 1; at(TokenKind::Star) || at(TokenKind::Slash); ++terms) {
        check_size(terms, kMaxTerms, "terms");
        const char op = take().kind == TokenKind::Star ? '*' : '/';
        left = binary_expression(Expr::Kind::Binary, std::move(left), op, "", parse_unary());
    }
    return left;
}

// unary = ( "-" | "+" ) unary | postfix ;
Expr Parser::parse_unary() {
    if (!at(TokenKind::Minus) && !at(TokenKind::Plus)) return parse_postfix();
    enter_nesting();
    Expr unary;
    unary.kind = Expr::Kind::Unary;
    const Token sign = take();
    unary.op = sign.kind == TokenKind::Minus ? '-' : '+';
    unary.operands.push_back(parse_unary());
    unary.span = {sign.span.begin, unary.operands[0].span.end, sign.span.origin};
    --depth_;
    return unary;
}

// postfix = primary { "." identifier | "[" expression "]" } ;
Expr Parser::parse_postfix() {
    Expr value = parse_primary();
    for (int steps = 0; at(TokenKind::Dot) || at(TokenKind::LBracket); ++steps) {
        // A chain this long is a broken or hostile file.
        if (steps == kMaxParseDepth)
            fail_and_skip_file(peek(), "the expression is nested too deeply (more than 200 levels)");
        Expr access;
        if (take().kind == TokenKind::Dot) {
            Token component = expect(TokenKind::Identifier, "a component name (x, y or z) after '.'");
            access.kind = Expr::Kind::Component;
            access.text = std::string(component.text);
            access.span = {value.span.begin, component.span.end, value.span.origin};
            access.operands.push_back(std::move(value));
        } else {
            enter_nesting();
            access.kind = Expr::Kind::Index;
            access.operands.push_back(std::move(value));
            access.operands.push_back(parse_expression());
            access.span = {access.operands[0].span.begin, expect(TokenKind::RBracket, "']' after the index").span.end,
                           access.operands[0].span.origin};
            --depth_;
        }
        value = std::move(access);
    }
    return value;
}

// conditional = "if" expression "{" expression "}" "else" ( "{" expression "}" | conditional ) ;
Expr Parser::parse_conditional() {
    const Token keyword = take();
    enter_nesting();
    Expr conditional;
    conditional.kind = Expr::Kind::Conditional;
    conditional.operands.push_back(parse_expression());
    if (at(TokenKind::Equals)) fail(peek(), "'=' gives a name its value; to compare two values write '=='");
    expect(TokenKind::LBrace, "'{' before the value if the condition holds");
    conditional.operands.push_back(parse_expression());
    expect(TokenKind::RBrace, "'}' after the value");
    if (!at_word("else"))
        fail(peek(), "expected 'else' and the value otherwise: 'if c { a } else { b }', found " + describe(peek()));
    take();
    if (at_word("if")) {
        conditional.operands.push_back(parse_conditional());
        conditional.span = {keyword.span.begin, conditional.operands.back().span.end, keyword.span.origin};
    } else {
        expect(TokenKind::LBrace, "'{' before the value otherwise");
        conditional.operands.push_back(parse_expression());
        conditional.span = {keyword.span.begin, expect(TokenKind::RBrace, "'}' after the value").span.end,
                            keyword.span.origin};
    }
    --depth_;
    return conditional;
}

// The comma-separated expressions of a call, vector or list, after its opening bracket, and
// the closing one.
void Parser::parse_list(Expr& value, TokenKind close, const char* what) {
    enter_nesting();
    take();  // the opening bracket
    if (!at(close) || value.kind == Expr::Kind::Vector) {
        for (;;) {
            value.operands.push_back(parse_expression());
            if (at(TokenKind::Comma)) {
                check_size(value.operands.size(), kMaxTerms, "values");
                take();
                if (close == TokenKind::RBracket && at(close)) break;  // [a, b,] as in most languages
                continue;
            }
            if (at(close)) break;
            fail(peek(), "expected ',' or " + describe(close) + " in " + what + ", found " + describe(peek()));
        }
    }
    value.span.end = take().span.end;
    --depth_;
}

// primary = number | string | "true" | "false" | conditional | identifier [ "(" arguments ")" ]
//         | identifier body | "(" expression { "," expression } ")" | "[" [ expressions ] "]" ;
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
            if (token.text == "if") return parse_conditional();
            if (token.text == "true" || token.text == "false") {
                value.kind = Expr::Kind::Bool;
                value.number = take().text == "true" ? 1 : 0;
                return value;
            }
            value.kind = Expr::Kind::Name;
            value.text = std::string(take().text);
            if ((value.text == "material" || value.text == "transform" || find_pattern_spec(value.text)) &&
                at(TokenKind::LBrace)) {  // a block as a value
                value.kind = Expr::Kind::Block;
                value.body = std::make_shared<BodyCode>();
                parse_body(*value.body, value.text);
                value.span.end = value.body->close_brace.end;
                return value;
            }
            if (!at(TokenKind::LParen)) return value;
            value.kind = Expr::Kind::Call;
            parse_list(value, TokenKind::RParen, "the call");
            return value;
        case TokenKind::LBracket:
            value.kind = Expr::Kind::List;
            parse_list(value, TokenKind::RBracket, "the list");
            return value;
        case TokenKind::LParen: {
            value.kind = Expr::Kind::Vector;
            parse_list(value, TokenKind::RParen, "vector");
            if (value.operands.size() != 1) return value;
            Expr inner = std::move(value.operands[0]);  // (a) is a, in parentheses
            inner.span = value.span;
            return inner;
        }
        default:
            if (token.kind == TokenKind::Star && token.span.begin > 0 && file_.text()[token.span.begin - 1] == '*')
                fail(token, "'**' is not an operator; for a to the power b write pow(a, b)");
            if (token.kind == TokenKind::Less)  // POV-Ray's <x, y, z>
                fail(token, "expected a value, found '<'; a vector is written (x, y, z) in parentheses");
            fail(token, "expected a value, found " + describe(token));
    }
}

}  // namespace tracer
