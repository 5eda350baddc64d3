// The syntax tree: a scene file as written: statements (blocks, names, loops, conditions,
// functions, groups, includes) whose values are expressions. The parser builds it; the interpreter (interpreter.h)
// evaluates it into the blocks of plain values (evaluated_scene.h) that validation checks.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "base/source.h"
#include "lang/internal/take_apart.h"

namespace tracer {

struct BodyCode;

struct Expr {
    enum class Kind {
        Number,       // a literal: `number`
        String,       // a literal: `text`
        Bool,         // true or false: `number` 1 or 0
        Name,         // a let, param or loop name, or else a word (`sah`, a material): `text`
        Vector,       // (a, b, c): `operands`
        List,         // [a, b, c]: `operands`
        Unary,        // `op` ('-' or '+') applied to operands[0]
        Not,          // not operands[0]
        Binary,       // operands[0] `op` operands[1], op one of + - * /
        Compare,      // operands[0] `text` operands[1], text one of == != < <= > >=
        Logical,      // operands[0] `text` operands[1] `text` ..., text "and" or "or" (flat: no depth)
        Conditional,  // if operands[0] { operands[1] } else { operands[2] }
        Call,         // `text`(operands...)
        Component,    // operands[0].`text` (x, y or z)
        Index,        // operands[0][operands[1]]
        Block,        // a block `{ ... }`: `body`; `text` its kind when written as a value (material { ... })
    };
    Kind kind = Kind::Number;
    Span span;
    double number = 0;
    std::string text;
    char op = 0;
    std::vector<Expr> operands;
    std::shared_ptr<BodyCode> body;

    Expr() = default;
    Expr(Expr&&) noexcept = default;
    Expr& operator=(Expr&&) noexcept = default;
    Expr(const Expr&) = delete;  // a copy would recurse down a chain as long as the file
    Expr& operator=(const Expr&) = delete;
    // Takes the tree apart iteratively: a chain a + b + ... of a million terms is a million
    // levels deep, too deep for a recursive destruction.
    ~Expr();
};

inline Expr::~Expr() {
    take_apart(operands);
}

struct EntryCode {
    std::string key;
    Span key_span;
    Expr value;
};

struct BodyCode {
    Span open_brace;
    Span close_brace;
    std::vector<EntryCode> entries;
};

struct Statement {
    enum class Kind {
        Block,     // kind [name] { entries }
        Let,       // let name = value
        Assign,    // name = value (a name already defined, in the same function or file level)
        While,     // while value { statements }
        Param,     // param name = value (the command line may set it: -D name=value)
        For,       // for name in value..end { statements }, or for name in value { statements } (a list)
        If,        // if value { statements } else { otherwise }
        Function,  // fn name(parameters) { statements }
        Return,    // return [value]
        Call,      // value (a call) as a statement: the blocks it makes
        Group,     // group { body (its placement) statements }, or union, merge, intersection, difference
        Include,   // include "path"
    };
    Kind kind = Kind::Block;
    Span keyword;      // the block's kind or the statement's keyword
    std::string word;  // Block: its kind; Group: its keyword; Include: the path
    std::string name;  // Block: its name (may be empty); Let, Param, For: the name bound
    Span name_span;    // Include: the path's span
    BodyCode body;     // Block
    bool broken =
        false;   // Block: a syntax error was reported inside; do not validate further. Group: its '}' is missing
    Expr value;  // Let, Param, Assign, Return, Call: the value; For: the first number or the list; If, While: the
                 // condition
    Expr end;    // For: the end of the range (not included)
    bool over_list = false;                                // For: over the elements of a list (no end)
    bool has_value = false;                                // Return: a value is returned
    std::vector<Statement> statements;                     // For, While, If, Function, Group: the body
    std::vector<Statement> otherwise;                      // If: the else branch (an else-if is one If statement in it)
    std::vector<std::pair<std::string, Span>> parameters;  // Function
    Span end_brace;                                        // For, If, Function, Group: the closing '}'
    // Function: a shape value, `let NAME = sphere { ... }` (a function of no parameters making
    // that block, placed by its name alone); Call: a name alone, placing a shape value.
    bool shape_value = false;
};

struct Program {
    std::vector<Statement> statements;
};

}  // namespace tracer
