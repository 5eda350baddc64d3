// The program compiled from the syntax tree (syntax_tree.h) for the interpreter: every name
// resolved to a slot, every built-in found, every block's table looked up, each statement's
// mistakes that do not depend on values (undefined names, names defined twice, unknown
// functions) reported once, however often the code runs. Spans are as written (the origin of
// the file as compiled); the interpreter gives them the origin of the iteration, call or
// include that runs them.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "base/source.h"
#include "lang/internal/runtime_value.h"

namespace tracer {

struct Builtin;
struct BlockSpec;
struct KeySpec;
struct CompiledBody;

struct ExprCode {
    enum class Op : uint8_t {
        Constant,     // `constant`
        FrameValue,   // the frame's clock value FrameValue(`index`) (interpreter.h)
        Local,        // slot `index` of the running frame
        Global,       // slot `index` of the top-level frame (a name defined at the top level)
        Capture,      // the running function's captured value `index`
        Self,         // the running function itself (its own name in its body)
        Word,         // a name bound to nothing at the top of an entry: the word `text` (sah, a material)
        Vector,       // (operands...)
        List,         // [operands...]
        Negate,       // -operands[0]
        Plus,         // +operands[0]
        Not,          // not operands[0]
        Arithmetic,   // operands[0] op operands[1] op ..., `text` the operators, each + - * /
        Compare,      // operands[0] `text` operands[1]
        And,          // operands[0] and operands[1] and ...
        Or,           // operands[0] or operands[1] or ...
        Builtin,      // `builtin`(operands...)
        Call,         // operands[0](operands[1...]): a user function
        Component,    // operands[0].x, .y or .z (`index` 0, 1, 2)
        Index,        // operands[0][operands[1]]
        Conditional,  // if operands[0] { operands[1] } else { operands[2] }
        Block,        // material { ... } or transform { ... } as a value: `block`
    };
    Op op = Op::Constant;
    uint32_t index = 0;
    Span span;
    RuntimeValue constant;
    const Builtin* builtin = nullptr;
    std::string text;  // Word: the word; Call: the function's name as written; Compare: the operator
    std::vector<ExprCode> operands;
    std::shared_ptr<const CompiledBody> block;

    ExprCode() = default;
    ExprCode(ExprCode&&) noexcept = default;
    ExprCode& operator=(ExprCode&&) noexcept = default;
    ExprCode(const ExprCode&) = delete;
    ExprCode& operator=(const ExprCode&) = delete;
    ~ExprCode();  // iterative, as Expr's: a chain may be a million long
};

struct CompiledEntry {
    std::string key;
    Span key_span;
    const KeySpec* spec = nullptr;  // the key's row in its block's table, if there is one
    bool nested = false;            // a { ... } body follows the key: `body`; else `value`
    ExprCode value;
    std::shared_ptr<const CompiledBody> body;
};

struct CompiledBody {
    std::string kind;                 // the block's kind ("material", or the key that opened it)
    const BlockSpec* spec = nullptr;  // its table, if it has one
    Span open_brace, close_brace;
    std::vector<CompiledEntry> entries;
};

struct StatementCode;

// A function as compiled: `parameters` slots first, then its locals, `slots` in all.
struct FunctionCode {
    std::string name;
    Span name_span;
    uint32_t parameters = 0;
    uint32_t slots = 0;
    uint32_t file_origin = 0;  // the origin its spans were compiled with (its file)
    std::vector<StatementCode> steps;
    // Where each captured value is found when the function is defined: a Local, Capture, Self
    // or Global node of the defining code.
    std::vector<ExprCode> captures;
    ~FunctionCode();
};

struct StatementCode {
    enum class Op : uint8_t {
        Block,     // kind [name] { body }: a block made
        Let,       // slot `slot` = value (a let, or an assignment to a name of this level)
        Param,     // global slot `slot` = value, or the command line's -D value for `name`
        Range,     // for slot `slot` in value..end { steps }
        Each,      // for slot `slot` in value (a list) { steps }
        While,     // while value { steps }
        If,        // if value { steps } else { otherwise }
        Function,  // slot `slot` = the function `function`, with its captures taken now
        Return,    // return value (`has_value`) from the running function
        Call,      // value (a call) run for the blocks it makes
        Print,     // print(a, b, ...): value, a list of them, written out
        Group,     // group { body (its placement) steps }, or a solid's block (word: union, ...)
        Include,   // the file `word` (origin `origin`), compiled in place: steps
    };
    Op op = Op::Block;
    Span keyword;
    std::string word;  // Block: the kind; Group: group or a solid's keyword; Include: the path
    std::string name;  // Block: its name; Let, Param, loops, Function: the name bound
    Span name_span;
    uint32_t slot = 0;
    uint32_t origin = 0;    // Include: the origin its file was compiled with
    bool broken = false;    // Block: a syntax error was reported inside
    bool unclosed = false;  // Group: its '}' is missing (reported; its contents were cut short)
    bool has_value = false;
    bool top_level = false;  // Range: outside every other loop (an empty range is warned about)
    ExprCode value, end;
    std::shared_ptr<const CompiledBody> body;
    std::shared_ptr<const FunctionCode> function;
    std::vector<StatementCode> steps, otherwise;
};

inline FunctionCode::~FunctionCode() = default;

}  // namespace tracer
