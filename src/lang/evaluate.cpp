// The interpreter's expressions: values computed from compiled nodes, user functions called,
// and an entry's value handed to validation with its spans.
#include <algorithm>
#include <array>
#include <cmath>

#include "base/big_stack.h"
#include "lang/internal/builtins.h"
#include "lang/internal/interpreter_class.h"
#include "lang/schema.h"
#include "scene/pattern.h"

namespace tracer {

// Non-finite results (1e300 * 1e300, 0 * huge / tiny) are errors where they happen.
RuntimeValue Interpreter::finite(RuntimeValue value, Span span) {
    bool ok = true;
    if (value.is_number()) ok = std::isfinite(value.x[0]);
    if (value.is_vector())
        for (double c : value.components()) ok = ok && std::isfinite(c);
    if (!ok) fail(span, "this expression's value is not finite (too large for a double)");
    return value;
}

double Interpreter::number_operand(const RuntimeValue& value, Span span, const std::string& what) {
    if (value.kind == RuntimeValue::Kind::Broken) throw EvaluationError{};
    if (!value.is_number()) fail(span, what + " must be a number; this is " + runtime_kind(value));
    return value.x[0];
}

bool Interpreter::condition(const ExprCode& node) {
    const RuntimeValue value = evaluate(node);
    if (value.kind != RuntimeValue::Kind::Bool)
        fail(node.span, "a condition must be true or false; this is " + runtime_kind(value) +
                            (value.is_number() ? " (compare it, as in 'x != 0')" : ""));
    return value.x[0] != 0;
}

// The value of `node`. Its frame is kept small (each call of a scene's function nests it
// again on the native stack): the cases with arrays or messages are functions of their own.
RuntimeValue Interpreter::evaluate(const ExprCode& node) {
    if (++operations_ > limits_.max_operations) [[unlikely]]
        out_of_operations(node.span);
    switch (node.op) {
        case ExprCode::Op::Constant:
            if (node.constant.kind == RuntimeValue::Kind::Broken) throw EvaluationError{};  // reported when compiled
            return node.constant;
        case ExprCode::Op::FrameValue: return RuntimeValue::number(frame_value(frame_, FrameValue(node.index)));
        case ExprCode::Op::Local:
        case ExprCode::Op::Global: {
            const RuntimeValue& value = node.op == ExprCode::Op::Local ? slot(node.index) : stack_[node.index];
            if (value.kind == RuntimeValue::Kind::Broken)
                throw EvaluationError{};  // its definition's error is reported
            return value;
        }
        case ExprCode::Op::Capture: {
            const RuntimeValue& value = running_.function().captures[node.index];
            if (value.kind == RuntimeValue::Kind::Broken) throw EvaluationError{};
            return value;
        }
        case ExprCode::Op::Self: return running_;
        case ExprCode::Op::Vector: return evaluate_vector(node);
        case ExprCode::Op::List: return evaluate_list(node);
        case ExprCode::Op::Negate:
        case ExprCode::Op::Plus: return evaluate_sign(node);
        case ExprCode::Op::Not: return RuntimeValue::boolean(!condition(node.operands[0]));
        case ExprCode::Op::Arithmetic: return evaluate_arithmetic(node);
        case ExprCode::Op::Compare: return evaluate_compare(node);
        case ExprCode::Op::And:
            for (const ExprCode& operand : node.operands)
                if (!condition(operand)) return RuntimeValue::boolean(false);
            return RuntimeValue::boolean(true);
        case ExprCode::Op::Or:
            for (const ExprCode& operand : node.operands)
                if (condition(operand)) return RuntimeValue::boolean(true);
            return RuntimeValue::boolean(false);
        case ExprCode::Op::Builtin: return evaluate_builtin(node);
        case ExprCode::Op::Call: return call(node, true);
        case ExprCode::Op::Component: return evaluate_component(node);
        case ExprCode::Op::Index: return evaluate_index(node);
        case ExprCode::Op::Conditional:
            return evaluate(condition(node.operands[0]) ? node.operands[1] : node.operands[2]);
        case ExprCode::Op::Block: return evaluate_block(node);
        case ExprCode::Op::Word: break;
    }
    fail_undefined(node);
}

void Interpreter::fail_undefined(const ExprCode& node) {
    fail(node.span, node.op == ExprCode::Op::Word ? "undefined name " + in_quotes(node.text) : "not a value");
}

RuntimeValue Interpreter::evaluate_vector(const ExprCode& node) {
    double components[16];
    std::vector<double> many;
    for (size_t i = 0; i < node.operands.size(); ++i) {
        const double c = number_operand(evaluate(node.operands[i]), node.operands[i].span, "a vector's component");
        if (i < 16) components[i] = c;
        if (i == 16) many.assign(components, components + 16);
        if (i >= 16) many.push_back(c);
    }
    if (node.operands.size() > 16) return RuntimeValue::vector(many);
    return RuntimeValue::vector({components, node.operands.size()});
}

RuntimeValue Interpreter::evaluate_sign(const ExprCode& node) {
    RuntimeValue value = evaluate(node.operands[0]);
    if (value.kind == RuntimeValue::Kind::Broken) throw EvaluationError{};
    if (!value.is_number() && !value.is_vector())
        fail(node.operands[0].span, std::string("'") + (node.op == ExprCode::Op::Negate ? '-' : '+') +
                                        "' applies to numbers and vectors; this is " + runtime_kind(value));
    if (node.op == ExprCode::Op::Plus) return value;
    if (value.object) {
        std::vector<double> negated;
        for (double c : value.components()) negated.push_back(-c);
        return RuntimeValue::vector(negated);
    }
    for (double& c : value.x) c = -c;
    return value;
}

RuntimeValue Interpreter::evaluate_component(const ExprCode& node) {
    const RuntimeValue value = evaluate(node.operands[0]);
    static const char* kNames[] = {"x", "y", "z"};
    if (!value.is_vector() || value.components().size() <= node.index)
        fail(node.operands[0].span,
             std::string("'.") + kNames[node.index] + "' needs a vector; this is " + runtime_kind(value));
    return RuntimeValue::number(value.components()[node.index]);
}

RuntimeValue Interpreter::evaluate_block(const ExprCode& node) {
    bool failed = false;
    auto block = std::make_shared<BlockObject>();
    block->kind = node.text;
    block->body = make_body(*node.block, failed);
    if (failed) throw EvaluationError{};
    RuntimeValue value;
    value.kind = RuntimeValue::Kind::Block;
    value.object = std::move(block);
    return value;
}

RuntimeValue Interpreter::evaluate_list(const ExprCode& node) {
    list_items_ += node.operands.size();
    if (list_items_ > limits_.max_list_items)
        stop(node.span,
             "the scene makes more than " + std::to_string(limits_.max_list_items) + " list items (the limit)");
    std::vector<RuntimeValue> items;
    items.reserve(node.operands.size());
    for (const ExprCode& operand : node.operands) {
        items.push_back(evaluate(operand));
        if (items.back().kind == RuntimeValue::Kind::Broken) throw EvaluationError{};
    }
    return RuntimeValue::list(std::move(items));
}

RuntimeValue Interpreter::evaluate_index(const ExprCode& node) {
    const RuntimeValue container = evaluate(node.operands[0]);
    const ExprCode& index_node = node.operands[1];
    const double index = number_operand(evaluate(index_node), index_node.span, "an index");
    size_t size = 0;
    if (container.kind == RuntimeValue::Kind::List)
        size = container.items().size();
    else if (container.is_vector())
        size = container.components().size();
    else
        fail(node.operands[0].span, "'[...]' picks from a list or a vector; this is " + runtime_kind(container));
    if (std::floor(index) != index || index < 0)
        fail(index_node.span, "an index is a whole number from 0; this is " + format_number(index));
    if (index >= double(size))
        fail(index_node.span, "index " + format_number(index) + " is past the end: " + runtime_kind(container) +
                                  (size == 0 ? " has none" : " has indexes 0 to " + std::to_string(size - 1)));
    if (container.kind == RuntimeValue::Kind::List) return container.items()[size_t(index)];
    return RuntimeValue::number(container.components()[size_t(index)]);
}

// A chain a + b - c ... (or a * b / c ...), folded left to right.
RuntimeValue Interpreter::evaluate_arithmetic(const ExprCode& node) {
    RuntimeValue result = evaluate(node.operands[0]);
    Span left = node.operands[0].span;
    for (size_t k = 1; k < node.operands.size(); ++k) {
        const ExprCode& operand = node.operands[k];
        const Span span{node.operands[0].span.begin, operand.span.end, node.span.origin};
        result = arithmetic(node.text[k - 1], result, evaluate(operand), left, operand.span, span);
        left = span;
    }
    return result;
}

// a `operation` b, the operands written at `a_span` and `b_span`, the whole at `span`.
RuntimeValue Interpreter::arithmetic(char operation, const RuntimeValue& a, const RuntimeValue& b, Span a_span,
                                     Span b_span, Span span) {
    if (a.is_number() && b.is_number()) {  // the common case first, with nothing to allocate
        if (operation == '/' && b.x[0] == 0) fail(b_span, "division by zero");
        const double x = a.x[0], y = b.x[0];
        const double result = operation == '+' ? x + y : operation == '-' ? x - y : operation == '*' ? x * y : x / y;
        if (!std::isfinite(result)) fail(span, "this expression's value is not finite (too large for a double)");
        return RuntimeValue::number(result);
    }
    const std::string op = std::string("'") + operation + "'";
    if (a.kind == RuntimeValue::Kind::String || b.kind == RuntimeValue::Kind::String)
        return join(operation, a, b, a_span, b_span, span);
    if (a.kind == RuntimeValue::Kind::Block || b.kind == RuntimeValue::Kind::Block)
        return scaled_pattern(operation, a, b, a_span, b_span, span);
    for (const auto& [operand, where] : {std::pair{&a, a_span}, std::pair{&b, b_span}}) {
        if (operand->kind == RuntimeValue::Kind::Broken) throw EvaluationError{};
        if (!operand->is_number() && !operand->is_vector())
            fail(where, op + " applies to numbers and vectors; this is " + runtime_kind(*operand));
    }
    std::vector<double> out;
    if (a.is_vector() && b.is_vector()) {
        if (operation == '*' || operation == '/')
            fail(span, op + " does not multiply two vectors; use dot(a, b) or cross(a, b)");
        const auto u = a.components(), v = b.components();
        if (u.size() != v.size())
            fail(span,
                 "the vectors have " + std::to_string(u.size()) + " and " + std::to_string(v.size()) + " components");
        for (size_t i = 0; i < u.size(); ++i) out.push_back(operation == '+' ? u[i] + v[i] : u[i] - v[i]);
        return finite(RuntimeValue::vector(out), span);
    }
    // A vector and a number: scaled (v * s, s * v, v / s); adding them is an error.
    if (operation == '+' || operation == '-')
        fail(span, op + " needs two numbers or two vectors; this is a number and a vector");
    const RuntimeValue& vector = a.is_vector() ? a : b;
    const double scalar = a.is_vector() ? b.x[0] : a.x[0];
    if (operation == '/' && a.is_number()) fail(span, "a number cannot be divided by a vector");
    if (operation == '/' && scalar == 0) fail(b_span, "division by zero");
    for (double c : vector.components()) out.push_back(operation == '*' ? c * scalar : c / scalar);
    return finite(RuntimeValue::vector(out), span);
}

RuntimeValue Interpreter::scaled_pattern(char operation, const RuntimeValue& a, const RuntimeValue& b, Span a_span,
                                         Span b_span, Span span) {
    if (a.kind == RuntimeValue::Kind::Broken || b.kind == RuntimeValue::Kind::Broken) throw EvaluationError{};
    const bool pattern_first = a.kind == RuntimeValue::Kind::Block;
    const RuntimeValue& pattern = pattern_first ? a : b;
    const RuntimeValue& factor = pattern_first ? b : a;
    const Span pattern_span = pattern_first ? a_span : b_span, factor_span = pattern_first ? b_span : a_span;
    const std::string op = std::string("'") + operation + "'";
    if (!find_pattern_spec(pattern.block().kind))
        fail(pattern_span,
             op + " applies to numbers and vectors (and scales patterns); this is " + runtime_kind(pattern));
    const bool colour = factor.is_number() || (factor.is_vector() && factor.components().size() == 3);
    if (!colour || (operation != '*' && !(operation == '/' && pattern_first && factor.is_number())))
        fail(span, "a pattern is scaled by a number or a colour: 0.1 * pattern, pattern * (1, 0.5, 0.5), pattern / 10");
    if (operation == '/' && factor.x[0] == 0) fail(factor_span, "division by zero");
    // The factor, channel by channel, times any `multiply` the pattern already has.
    const auto channels = [](const RuntimeValue& v) {
        return v.is_number() ? std::array{v.x[0], v.x[0], v.x[0]} : std::array{v.x[0], v.x[1], v.x[2]};
    };
    std::array<double, 3> scale = channels(factor);
    if (operation == '/')
        for (double& c : scale) c = 1 / c;
    auto body = std::make_shared<Body>(*pattern.block().body);
    auto existing = std::find_if(body->entries.begin(), body->entries.end(),
                                 [](const Entry& entry) { return entry.key == "multiply"; });
    if (existing == body->entries.end()) {
        Entry entry;
        entry.key = "multiply";
        entry.key_span = at(span);
        body->entries.push_back(entry);
        existing = body->entries.end() - 1;
        existing->value.kind = PlainValue::Kind::Number;
        existing->value.number = 1;
    }
    PlainValue& value = existing->value;
    if (value.kind == PlainValue::Kind::Number || value.kind == PlainValue::Kind::Vector) {
        std::array<double, 3> before{value.number, value.number, value.number};
        if (value.kind == PlainValue::Kind::Vector && value.components.size() == 3)
            before = {value.components[0], value.components[1], value.components[2]};
        const std::array<double, 3> after{before[0] * scale[0], before[1] * scale[1], before[2] * scale[2]};
        value.span = at(span);
        if (after[0] == after[1] && after[1] == after[2]) {  // grey: one number (one message if it is wrong)
            value.kind = PlainValue::Kind::Number;
            value.number = after[0];
        } else {
            value.kind = PlainValue::Kind::Vector;
            value.components = {after[0], after[1], after[2]};
            value.component_spans.assign(3, value.span);
        }
    }
    auto scaled = std::make_shared<BlockObject>();
    scaled->kind = pattern.block().kind;
    scaled->body = std::move(body);
    RuntimeValue out;
    out.kind = RuntimeValue::Kind::Block;
    out.object = std::move(scaled);
    return out;
}

// a + b where one is a string: the two strings joined, or an error that says how to write it.
RuntimeValue Interpreter::join(char operation, const RuntimeValue& a, const RuntimeValue& b, Span a_span, Span b_span,
                               Span span) {
    if (a.kind == RuntimeValue::Kind::Broken || b.kind == RuntimeValue::Kind::Broken) throw EvaluationError{};
    if (operation != '+')
        fail(span, std::string("'") + operation + "' does not apply to strings; '+' joins two strings");
    for (const auto& [operand, where] : {std::pair{&a, a_span}, std::pair{&b, b_span}}) {
        if (operand->kind != RuntimeValue::Kind::String)
            fail(where, "'+' joins a string only to a string; this is " + runtime_kind(*operand) +
                            ": write str(...) around it to make it one");
    }
    if (a.text().size() + b.text().size() > kMaxStringBytes)
        fail(span,
             "this string would be longer than " + format_number(double(kMaxStringBytes)) + " characters (the limit)");
    return RuntimeValue::string(a.text() + b.text());
}

RuntimeValue Interpreter::evaluate_compare(const ExprCode& node) {
    const RuntimeValue a = evaluate(node.operands[0]), b = evaluate(node.operands[1]);
    const std::string& op = node.text;
    for (const RuntimeValue* operand : {&a, &b}) {
        if (operand->kind == RuntimeValue::Kind::Broken) throw EvaluationError{};
        const ExprCode& written = node.operands[operand == &a ? 0 : 1];
        const bool comparable =
            operand->is_number() ||
            ((op == "==" || op == "!=") && (operand->is_vector() || operand->kind == RuntimeValue::Kind::Bool ||
                                            operand->kind == RuntimeValue::Kind::String));
        if (!comparable)
            fail(written.span,
                 "'" + op + "' compares " +
                     (op == "==" || op == "!=" ? "numbers, vectors, booleans or strings" : std::string("numbers")) +
                     "; this is " + runtime_kind(*operand));
    }
    if (op == "==" || op == "!=") {
        if (a.kind != b.kind || (a.is_vector() && a.components().size() != b.components().size()))
            fail(node.span, "'" + op + "' compares two values of the same kind; this is " + runtime_kind(a) + " and " +
                                runtime_kind(b));
        return RuntimeValue::boolean(equal_values(a, b) == (op == "=="));
    }
    const double x = a.x[0], y = b.x[0];
    return RuntimeValue::boolean(op == "<" ? x < y : op == "<=" ? x <= y : op == ">" ? x > y : x >= y);
}

RuntimeValue Interpreter::evaluate_builtin(const ExprCode& node) {
    RuntimeValue args[4];
    Span spans[4];
    const size_t n = node.operands.size();  // the arity, checked when compiled (at most 3)
    for (size_t i = 0; i < n; ++i) {
        args[i] = evaluate(node.operands[i]);
        if (args[i].kind == RuntimeValue::Kind::Broken) throw EvaluationError{};
        spans[i] = node.operands[i].span;
    }
    try {
        return finite(node.builtin->body(BuiltinArguments(node.builtin->name, {args, n}, {spans, n}, node.span)),
                      node.span);
    } catch (const BuiltinError& error) {
        fail(error.span, error.message);
    }
}

RuntimeValue Interpreter::call(const ExprCode& node, bool for_value) {
    // Step 1: the function and its arguments, in the caller's frame.
    const RuntimeValue callee = evaluate(node.operands[0]);
    if (callee.kind != RuntimeValue::Kind::Function)
        fail(node.operands[0].span, in_quotes(node.text) + " is " + runtime_kind(callee) + ", not a function");
    const FunctionCode& code = *callee.function().code;
    const size_t given = node.operands.size() - 1;
    if (given != code.parameters) {
        diagnostics_.error(sources_, at(node.span), arguments_expected(code.name, code.parameters, given));
        throw EvaluationError{};
    }
    if (call_depth_ >= limits_.max_call_depth)
        stop(node.span, "calls nest more than " + std::to_string(limits_.max_call_depth) +
                            " deep (the limit): a recursion that does not stop?");
    if (const size_t used = stack_used_since(stack_top_, TRACER_STACK_ADDRESS()); used > kBigStackBytes / 2)
        stop(node.span, "calls nest " + std::to_string(call_depth_) + " deep and fill the interpreter's " +
                            std::to_string(kBigStackBytes / 2 >> 20) + " MiB of stack (about " +
                            std::to_string(used / std::max<size_t>(call_depth_, 1) >> 10) +
                            " KiB a call here, before the limit of " + std::to_string(limits_.max_call_depth) +
                            " calls): a recursion that does not stop?");
    const size_t base = stack_.size();
    stack_.resize(base + code.slots);
    for (size_t i = 0; i < given; ++i) {
        RuntimeValue argument = evaluate(node.operands[i + 1]);
        if (argument.kind == RuntimeValue::Kind::Broken) {
            stack_.resize(base);
            throw EvaluationError{};
        }
        stack_[base + i] = std::move(argument);
    }
    // Step 2: its body, in a frame of its own.
    const std::string_view name = sources_.file(code.name_span).slice(code.name_span);
    bool gave_value = false, failed_inside = false;
    RuntimeValue result;
    {
        struct Restore {
            Interpreter& machine;
            size_t frame_base;
            RuntimeValue running;
            bool making_blocks, step_failed;
            size_t stack_size;
            ~Restore() {
                machine.frame_base_ = frame_base;
                machine.running_ = std::move(running);
                machine.making_blocks_ = making_blocks;
                machine.step_failed_ = machine.step_failed_ || step_failed;
                machine.stack_.resize(stack_size);
                machine.contexts_.pop_back();
                --machine.call_depth_;
            }
        } restore{*this, frame_base_, running_, making_blocks_, step_failed_, base};
        contexts_.push_back({RunContext::Kind::Call, node.span, name, 0, code.file_origin});
        ++call_depth_;
        frame_base_ = base;
        running_ = callee;
        if (for_value) making_blocks_ = false;
        returned_value_ = false;
        step_failed_ = false;
        const Flow flow = run_steps(code.steps);
        gave_value = flow == Flow::Return && returned_value_;
        failed_inside = step_failed_;
        returned_value_ = false;
        result = std::move(returned_);
        returned_ = RuntimeValue{};
    }
    // Step 3: what the caller expected.
    if (result.kind == RuntimeValue::Kind::Broken) throw EvaluationError{};  // reported inside
    if (for_value && !gave_value) {
        if (failed_inside || stopped_ || diagnostics_.saturated()) throw EvaluationError{};  // reported inside
        fail(node.span, in_quotes(code.name) + " gives no value here: its body ends without 'return VALUE'");
    }
    if (!for_value && gave_value)
        fail(node.span, in_quotes(code.name) +
                            " gives a value, which a statement leaves unused; keep it with 'let NAME = " + code.name +
                            "(...)'");
    return result;
}

// An entry's value as validation reads it, with the spans of what wrote it: a word, or the
// value computed; false if it had an error (reported).
bool Interpreter::entry_value(const CompiledEntry& entry, PlainValue& out) {
    const ExprCode& node = entry.value;
    const KeySpec* key = entry.spec;
    out.span = at(node.span);
    // A param the command line set, used as it is: messages about it say where it came from.
    if (node.op == ExprCode::Op::Global && !command_line_.empty())
        if (auto set = command_line_.find(node.index); set != command_line_.end())
            out.span.origin = sources_.add_command_line(out.span, set->second);
    if (node.op == ExprCode::Op::Word) {
        out.kind = PlainValue::Kind::Identifier;
        out.text = node.text;
        return true;
    }
    const RuntimeValue value = evaluate(node);
    if (key && key->type == ValueType::Path && value.kind != RuntimeValue::Kind::String) {
        if (value.kind == RuntimeValue::Kind::Broken) throw EvaluationError{};
        if (node.op == ExprCode::Op::Constant)
            fail(node.span, path_expected(entry.key, sources_.file(node.span).slice(node.span)));
        fail(node.span, "'" + entry.key + "' expects a string (a file path); this is " + runtime_kind(value));
    }
    if (plain_value(value, out.span, out)) {
        // Written as (a, b, c): each component points at its own expression.
        if (node.op == ExprCode::Op::Vector && node.operands.size() == out.components.size())
            for (size_t i = 0; i < out.components.size(); ++i) out.component_spans[i] = at(node.operands[i].span);
        return true;
    }
    switch (value.kind) {
        case RuntimeValue::Kind::Block: {
            const std::string& kind = value.block().kind;
            const bool pattern = find_pattern_spec(kind) != nullptr;
            const std::string_view wanted = !key                                       ? std::string_view(kind)
                                            : key->type == ValueType::MaterialRef      ? "material"
                                            : key->type == ValueType::Paint && pattern ? std::string_view(kind)
                                            : key->type == ValueType::Paint            ? "pattern"
                                            : key->block                               ? key->block->kind
                                                                                       : std::string_view();
            if (wanted != kind && pattern && key && key->type == ValueType::Triple)
                fail(node.span, "'" + entry.key +
                                    "' takes a colour, not a pattern: only a material's ka and kd take "
                                    "patterns (kd " +
                                    kind + " { ... })");
            if (wanted != kind)
                fail(node.span, "'" + entry.key + "' takes " +
                                    (wanted.empty()         ? std::string("no block")
                                     : wanted == "material" ? std::string("a material")
                                                            : "a " + std::string(wanted) + " { ... } block") +
                                    "; this is a " + kind);
            out.kind = PlainValue::Kind::Block;
            out.body = value.block().body;
            out.text = kind;
            return true;
        }
        case RuntimeValue::Kind::List:
            if (!key || key->type == ValueType::ColorMap) {
                // Checked for size before it is copied: a list of a million stops is refused, not made.
                if (value.items().size() > kMostColorStops)
                    fail(node.span, "a colour map holds at most " + std::to_string(kMostColorStops) +
                                        " stops; this list has " + std::to_string(value.items().size()));
                if (plain_list(value, out.span, out)) return true;
                fail(node.span, "'" + entry.key +
                                    "' takes a list of stops [value, colour], as in "
                                    "[[0, (1, 0, 0)], [1, 1]]; an item here is " +
                                    first_unplain_kind(value));
            }
            fail(node.span, "'" + entry.key + "' takes one value, not a list; pick one with [i], as in 'list[0]'");
        case RuntimeValue::Kind::Function:
            fail(node.span, "'" + entry.key + "' takes a value, not a function; call it, as in 'f(...)'");
        case RuntimeValue::Kind::Broken: throw EvaluationError{};
        default: break;  // the plain kinds, done above
    }
    return false;
}

// `out` as the list of `value`'s items, each made plain by `item` (false at one that is not).
template <typename ItemRule>
static bool plain_items(const RuntimeValue& value, Span span, PlainValue& out, ItemRule item) {
    out.kind = PlainValue::Kind::List;
    out.span = span;
    out.items.resize(value.items().size());
    for (size_t i = 0; i < out.items.size(); ++i)
        if (!item(value.items()[i], span, out.items[i])) return false;
    return true;
}

// A stop of a colour map: a plain value, or a short list of plain values.
static bool plain_stop(const RuntimeValue& item, Span span, PlainValue& out) {
    if (item.kind != RuntimeValue::Kind::List) return plain_value(item, span, out);
    constexpr size_t kMostStopItems = 16;
    return item.items().size() <= kMostStopItems && plain_items(item, span, out, plain_value);
}

bool plain_list(const RuntimeValue& value, Span span, PlainValue& out) {
    return plain_items(value, span, out, plain_stop);
}

std::string first_unplain_kind(const RuntimeValue& value) {
    for (const RuntimeValue& item : value.items()) {
        PlainValue ignored;
        if (plain_stop(item, Span{}, ignored)) continue;
        if (item.kind != RuntimeValue::Kind::List) return runtime_kind(item);
        for (const RuntimeValue& inner : item.items())
            if (!plain_value(inner, Span{}, ignored)) return runtime_kind(inner);
        return runtime_kind(item);
    }
    return "";
}

bool plain_value(const RuntimeValue& value, Span span, PlainValue& out) {
    out.span = span;
    switch (value.kind) {
        case RuntimeValue::Kind::Number: out.kind = PlainValue::Kind::Number, out.number = value.x[0]; return true;
        case RuntimeValue::Kind::Vector: {
            out.kind = PlainValue::Kind::Vector;
            const auto components = value.components();
            out.components.assign(components.begin(), components.end());
            out.component_spans.assign(components.size(), span);
            return true;
        }
        case RuntimeValue::Kind::Bool:  // as the validator reads a boolean: the word
            out.kind = PlainValue::Kind::Identifier, out.text = value.x[0] != 0 ? "true" : "false";
            return true;
        case RuntimeValue::Kind::String: out.kind = PlainValue::Kind::String, out.text = value.text(); return true;
        default: return false;
    }
}

}  // namespace tracer
