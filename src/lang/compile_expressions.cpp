// The compiler's expressions: names resolved, built-ins found, chains of + - * / made flat.
#include <algorithm>

#include "lang/internal/builtins.h"
#include "lang/internal/compile.h"
#include "lang/internal/suggest.h"
#include "lang/schema.h"

namespace tracer {

namespace {

ExprCode node_of(ExprCode::Op op, Span span) {
    ExprCode node;
    node.op = op;
    node.span = span;
    return node;
}

}  // namespace

ExprCode Compiler::compile_expression(const Expr& expr, bool top, bool word_key) {
    ExprCode node = node_of(ExprCode::Op::Constant, expr.span);
    auto operands = [&](ExprCode::Op op) {
        node.op = op;
        for (const Expr& operand : expr.operands) node.operands.push_back(compile_expression(operand));
        return std::move(node);
    };
    switch (expr.kind) {
        case Expr::Kind::Number: node.constant = RuntimeValue::number(expr.number); return node;
        case Expr::Kind::String: node.constant = RuntimeValue::string(expr.text); return node;
        case Expr::Kind::Bool: node.constant = RuntimeValue::boolean(expr.number != 0); return node;
        case Expr::Kind::Name: return compile_name(expr, top, word_key);
        case Expr::Kind::Vector: return operands(ExprCode::Op::Vector);
        case Expr::Kind::List: return operands(ExprCode::Op::List);
        case Expr::Kind::Unary: return operands(expr.op == '-' ? ExprCode::Op::Negate : ExprCode::Op::Plus);
        case Expr::Kind::Not: return operands(ExprCode::Op::Not);
        case Expr::Kind::Binary: return compile_arithmetic(expr);
        case Expr::Kind::Compare: node.text = expr.text; return operands(ExprCode::Op::Compare);
        case Expr::Kind::Logical: return operands(expr.text == "and" ? ExprCode::Op::And : ExprCode::Op::Or);
        case Expr::Kind::Conditional: return operands(ExprCode::Op::Conditional);
        case Expr::Kind::Call: return compile_call(expr);
        case Expr::Kind::Component: {
            static const std::string_view kNames[] = {"x", "y", "z"};
            const auto found = std::find(std::begin(kNames), std::end(kNames), expr.text);
            if (found == std::end(kNames))
                fail(expr.span, "a vector's components are x, y and z; found " + in_quotes(expr.text) +
                                    did_you_mean(expr.text, {"x", "y", "z"}));
            node.index = uint32_t(found - std::begin(kNames));
            return operands(ExprCode::Op::Component);
        }
        case Expr::Kind::Index: return operands(ExprCode::Op::Index);
        case Expr::Kind::Block: {
            if (expr.text.empty()) fail(expr.span, "a block { ... } is not a value here");
            bool failed = false;
            node.op = ExprCode::Op::Block;
            node.text = expr.text;
            const BlockSpec* spec = find_block_spec(expr.text);
            node.block = compile_body(*expr.body, expr.text, spec ? spec : find_pattern_spec(expr.text), failed);
            if (failed) throw CompileError{};
            return node;
        }
    }
    fail(expr.span, "not a value");
}

// a + b - c ... (or a * b / c ...) is a tree as deep as it is long, on its left side: walked
// down that side iteratively and made one node of operands and operators, so that no length of
// chain can exhaust the native stack (right operands are bounded by the parentheses' limit).
ExprCode Compiler::compile_arithmetic(const Expr& expr) {
    std::vector<const Expr*> chain;  // the operations down the left side, outermost first
    const Expr* leftmost = &expr;
    for (; leftmost->kind == Expr::Kind::Binary; leftmost = &leftmost->operands[0]) chain.push_back(leftmost);
    ExprCode node = node_of(ExprCode::Op::Arithmetic, expr.span);
    node.operands.reserve(chain.size() + 1);
    node.operands.push_back(compile_expression(*leftmost));
    for (size_t k = chain.size(); k-- > 0;) {
        node.text += chain[k]->op;
        node.operands.push_back(compile_expression(chain[k]->operands[1]));
    }
    return node;
}

// A bound name reads its slot; an unbound one at the top of an entry is a word for the
// validator (a material, `sah`), unless it is close to a name in scope, which makes it a
// misspelled name; a built-in constant (pi) comes after the scene's names and before a word,
// except for a key that takes a word.
ExprCode Compiler::compile_name(const Expr& expr, bool top, bool word_key) {
    ExprCode node;
    if (resolve(expr.text, functions_.size() - 1, expr.span, node)) return node;
    const BuiltinConstant* builtin = word_key ? nullptr : find_constant(expr.text);
    if (builtin && builtin->frame_value != FrameValue::None) {
        node = node_of(ExprCode::Op::FrameValue, expr.span);
        node.index = uint32_t(builtin->frame_value);
        return node;
    }
    if (builtin) {
        node = node_of(ExprCode::Op::Constant, expr.span);
        node.constant = RuntimeValue::number(builtin->value);
        return node;
    }
    const std::vector<std::string_view> names = names_in_scope();
    const std::string suggestion = names.empty() ? "" : did_you_mean(expr.text, names);
    if (top && (names_nan_or_infinity(expr.text) || suggestion.empty())) {
        node = node_of(ExprCode::Op::Word, expr.span);
        node.text = expr.text;
        return node;
    }
    if (names_nan_or_infinity(expr.text))
        fail(expr.span, "undefined name " + in_quotes(expr.text) + " (NaN and infinity are not allowed)");
    fail(expr.span, "undefined name " + in_quotes(expr.text) + suggestion);
}

// A call: of the function a name in scope holds, else of the built-in of that name.
ExprCode Compiler::compile_call(const Expr& expr) {
    const Span name_span{expr.span.begin, expr.span.begin + uint32_t(expr.text.size()), expr.span.origin};
    ExprCode node = node_of(ExprCode::Op::Call, expr.span);
    node.text = expr.text;
    ExprCode callee;
    if (resolve(expr.text, functions_.size() - 1, name_span, callee)) {
        node.operands.push_back(std::move(callee));
        for (const Expr& operand : expr.operands) node.operands.push_back(compile_expression(operand));
        return node;
    }
    const Builtin* function = find_builtin(expr.text);
    if (!function && expr.text == "print")
        fail(name_span, "'print(...)' is a statement on its own: it writes its values out and gives none");
    if (!function && (expr.text == "translate" || expr.text == "scale" || expr.text == "rotate"))
        fail(name_span, in_quotes(expr.text) +
                            " here is read as a call of a function, and there is none of that name: as a "
                            "placement it goes at the top of a group, before the group's first statement, or "
                            "inside a shape's block");
    if (!function) {
        std::vector<std::string_view> names = names_in_scope();
        for (const Builtin& builtin : all_builtins()) names.push_back(builtin.name);
        fail(name_span, "unknown function " + in_quotes(expr.text) + did_you_mean(expr.text, names));
    }
    node.op = ExprCode::Op::Builtin;
    node.builtin = function;
    for (const Expr& operand : expr.operands) node.operands.push_back(compile_expression(operand));
    if (node.operands.size() != function->arity)
        fail(expr.span, arguments_expected(expr.text, function->arity, node.operands.size()));
    return node;
}

}  // namespace tracer
