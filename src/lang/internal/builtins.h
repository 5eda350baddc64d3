// The built-in functions of the scene language: one table, one row per function with its name,
// arity, meaning and body (Lua's luaL_Reg is the model). The interpreter calls through it and
// the reference (grammar/reference.md) is generated from it, so a function cannot exist
// without its body or its documentation.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "base/source.h"
#include "lang/internal/runtime_value.h"
#include "lang/interpreter.h"

namespace tracer {

// Thrown by a body for an argument it cannot take: the interpreter reports `message` at `span`.
struct BuiltinError {
    Span span;
    std::string message;
};

// A call's evaluated arguments (their number already checked against the arity), as a body
// reads them: number(i) and vector(i) throw BuiltinError when argument i is of another kind.
class BuiltinArguments {
public:
    BuiltinArguments(std::string_view function, std::span<const RuntimeValue> values, std::span<const Span> spans,
                     Span call)
        : function_(function), values_(values), spans_(spans), call_(call) {}
    const RuntimeValue& operator[](size_t i) const { return values_[i]; }
    Span span(size_t i) const { return spans_[i]; }  // where argument i is written
    Span call() const { return call_; }              // the whole call
    double number(size_t i) const;
    std::span<const double> vector(size_t i) const;  // of 3 components
    const std::vector<RuntimeValue>& list(size_t i) const;

private:
    std::string_view function_;
    std::span<const RuntimeValue> values_;
    std::span<const Span> spans_;
    Span call_;
};

// One built-in function. The body returns its result, or throws BuiltinError; the interpreter
// checks that the result is finite.
struct Builtin {
    std::string_view name;
    size_t arity;
    std::string_view meaning;  // one sentence for the reference
    RuntimeValue (*body)(const BuiltinArguments& args);
};

// A name with a number (pi, or one of the animation's clock values, FrameTime's): found after
// the scene's own names, before a word.
struct BuiltinConstant {
    std::string_view name;
    double value;  // a fixed one's
    std::string_view meaning;
    FrameValue frame_value = FrameValue::None;  // else: the frame's value of that name
};
const std::vector<BuiltinConstant>& all_constants();
// The constant called `name`, or nullptr.
const BuiltinConstant* find_constant(std::string_view name);

// Every built-in, in the order the reference lists them.
const std::vector<Builtin>& all_builtins();
// The built-in called `name`, or nullptr.
const Builtin* find_builtin(std::string_view name);

}  // namespace tracer
