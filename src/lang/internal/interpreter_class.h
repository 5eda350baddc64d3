// The interpreter's class, shared by its two files: interpreter.cpp (statements, blocks, the
// contexts that give spans their origins) and evaluate.cpp (expressions and calls). Internal.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "base/big_stack.h"
#include "lang/internal/code.h"
#include "lang/internal/compile.h"
#include "lang/interpreter.h"

namespace tracer {

// `value` as validation reads it, at `span` (each component too), if it is a number, vector,
// boolean or string; false for the other kinds.
bool plain_value(const RuntimeValue& value, Span span, PlainValue& out);
// A list (a colour map) as a plain value, each item plain or a list of at most 16 plain values;
// false if some item is not.
bool plain_list(const RuntimeValue& value, Span span, PlainValue& out);
// What the first item of a list that plain_list refuses is ("a function").
std::string first_unplain_kind(const RuntimeValue& value);

// Thrown after an error while running has been reported: the entry or statement is dropped.
// Made just before it is thrown, deep in calls it may be: the stack is readied for unwinding.
struct EvaluationError {
    EvaluationError() { stack_about_to_unwind(); }
};
// Thrown when a limit is reached (reported): nothing more is run, however deep the calls are
// (one exception through them all, not one per level).
struct EvaluationStopped {
    EvaluationStopped() { stack_about_to_unwind(); }
};

// Where the code running now came from, innermost last: a loop iteration, a call or an include.
// Its origin (Sources) is made only when something made in it needs a span.
struct RunContext {
    enum class Kind : uint8_t { Iteration, Call, Include };
    Kind kind = Kind::Iteration;
    Span at;                   // the loop's keyword, the call or the include's path, as compiled
    std::string_view name;     // the loop's variable or the function's name
    double value = 0;          // the iteration's value (or, looping over a list, its index)
    uint32_t file_origin = 0;  // Call, Include: the origin the code was compiled with
    uint32_t origin = 0;
    bool has_origin = false;
};

class Interpreter {
public:
    Interpreter(Sources& sources, Diagnostics& diagnostics, const InterpretLimits& limits, BlockSink on_block);

    EvaluatedScene run(const SceneArguments& arguments);
    // After run() with `keep_code`: the same code run again for `frame` (nothing compiled
    // again), its blocks to `on_block`. Compile-time problems were reported by run().
    EvaluatedScene run_again(const FrameTime& frame, BlockSink on_block);
    // Whether run() keeps every statement's code for run_again (an animation's frames).
    void keep_code(bool keep) { keep_code_ = keep; }
    bool single_value(const Expr& expr, PlainValue& out);

private:
    enum class Flow { Next, Return };

    // Statements (interpreter.cpp).
    Flow run_steps(const std::vector<StatementCode>& steps);
    Flow run_step(const StatementCode& step);
    void run_block(const StatementCode& step);
    void run_binding(const StatementCode& step);
    Flow run_range(const StatementCode& step);
    Flow run_each(const StatementCode& step);
    Flow run_include(const StatementCode& step);
    bool count_iteration(const StatementCode& step);
    std::shared_ptr<Body> make_body(const CompiledBody& code, bool& failed);
    // The same, into `body`.
    void fill_body(const CompiledBody& code, Body& body, bool& failed);
    // The value of an entry: `value` computed at `node`, as the validator reads it.
    bool entry_value(const CompiledEntry& entry, PlainValue& out);

    // Expressions (evaluate.cpp).
    RuntimeValue evaluate(const ExprCode& node);
    RuntimeValue evaluate_arithmetic(const ExprCode& node);
    RuntimeValue arithmetic(char operation, const RuntimeValue& a, const RuntimeValue& b, Span a_span, Span b_span,
                            Span span);
    // A pattern times a number or a colour (either side; divided by a number): the pattern with
    // its `multiply` key times that.
    RuntimeValue scaled_pattern(char operation, const RuntimeValue& a, const RuntimeValue& b, Span a_span, Span b_span,
                                Span span);
    RuntimeValue join(char operation, const RuntimeValue& a, const RuntimeValue& b, Span a_span, Span b_span,
                      Span span);
    [[gnu::noinline]] RuntimeValue evaluate_compare(const ExprCode& node);
    bool condition(const ExprCode& node);
    [[gnu::noinline]] RuntimeValue evaluate_builtin(const ExprCode& node);
    [[gnu::noinline]] RuntimeValue evaluate_index(const ExprCode& node);
    RuntimeValue evaluate_list(const ExprCode& node);
    [[gnu::noinline]] RuntimeValue evaluate_vector(const ExprCode& node);
    [[gnu::noinline]] RuntimeValue evaluate_sign(const ExprCode& node);
    [[gnu::noinline]] RuntimeValue evaluate_component(const ExprCode& node);
    [[gnu::noinline]] RuntimeValue evaluate_block(const ExprCode& node);
    [[noreturn, gnu::noinline]] void fail_undefined(const ExprCode& node);
    // A user function called at `node`: for its value, or (`for_value` false) for its blocks.
    RuntimeValue call(const ExprCode& node, bool for_value);
    RuntimeValue finite(RuntimeValue value, Span at);
    double number_operand(const RuntimeValue& value, Span span, const std::string& what);
    [[noreturn]] void fail(Span at, std::string message);
    // Reports that a limit was reached at `at`, and stops everything.
    [[noreturn]] void stop(Span at, std::string message);
    // stop() for the operations limit (kept out of evaluate's frame).
    [[noreturn, gnu::noinline, gnu::cold]] void out_of_operations(Span at);

    // Slots.
    RuntimeValue& slot(uint32_t index) { return stack_[frame_base_ + index]; }

    // Origins: the span as compiled, given the origin of the context running it.
    uint32_t here() {
        if (contexts_.empty()) return 0;
        return contexts_.back().has_origin ? contexts_.back().origin : make_origins();
    }
    // Makes the origins of the innermost contexts that have none yet; returns the innermost's.
    uint32_t make_origins();
    Span at(Span span) { return {span.begin, span.end, here()}; }

    Sources& sources_;
    Diagnostics& diagnostics_;
    Compiler compiler_;
    EvaluatedScene scene_;
    std::vector<RuntimeValue> stack_;  // the top level's slots, then each call's
    size_t frame_base_ = 0;
    RuntimeValue running_;      // the function running (none at the top level)
    bool step_failed_ = false;  // a statement had an error (reported) since the call began
    RuntimeValue returned_;     // the value of the last 'return'
    bool returned_value_ = false;
    bool making_blocks_ = true;  // false while a function runs for its value
    std::vector<RunContext> contexts_;
    std::shared_ptr<const Group> current_group_;                  // the innermost group running
    std::map<std::string, RuntimeValue, std::less<>> overrides_;  // -D values, by name
    std::map<std::string, std::string, std::less<>> override_texts_;
    std::map<uint32_t, std::string> command_line_;  // global slots of params set by -D: "-D NAME=VALUE"
    size_t blocks_ = 0, iterations_run_ = 0, operations_ = 0, list_items_ = 0, call_depth_ = 0;
    bool stopped_ = false;  // a limit was hit: nothing more is run
    InterpretLimits limits_;
    bool keep_code_ = false;
    std::vector<std::vector<StatementCode>> kept_;  // every statement's code, with keep_code_
    FrameTime frame_;                               // the animation's clock at the frame being made
    BlockSink on_block_;
    const char* stack_top_ = nullptr;  // where the native stack began, for the guard in call()
};

}  // namespace tracer
