#include "lang/interpreter.h"

#include <cmath>
#include <filesystem>

#include "base/big_stack.h"
#include "lang/internal/interpreter_class.h"
#include "lang/internal/parser.h"
#include "lang/internal/suggest.h"
#include "lang/schema.h"

namespace tracer {

namespace fs = std::filesystem;

Interpreter::Interpreter(Sources& sources, Diagnostics& diagnostics, const InterpretLimits& limits, BlockSink on_block)
    : sources_(sources),
      diagnostics_(diagnostics),
      compiler_(sources, diagnostics),
      limits_(limits),
      on_block_(std::move(on_block)) {}

// The origins of the contexts running now that have none yet, outermost first (here() is the
// origin for spans evaluated now: the innermost context's, or the scene file's).
uint32_t Interpreter::make_origins() {
    size_t first = contexts_.size() - 1;
    while (first > 0 && !contexts_[first - 1].has_origin) --first;
    uint32_t outer = first == 0 ? 0 : contexts_[first - 1].origin;
    for (size_t k = first; k < contexts_.size(); ++k) {
        RunContext& context = contexts_[k];
        const Span at{context.at.begin, context.at.end, outer};
        switch (context.kind) {
            case RunContext::Kind::Iteration:
                context.origin = sources_.add_iteration(at, context.name, context.value);
                break;
            case RunContext::Kind::Call:
                context.origin = sources_.add_call(context.file_origin, at, context.name);
                break;
            case RunContext::Kind::Include: context.origin = sources_.add_include_again(context.file_origin, at); break;
        }
        context.has_origin = true;
        outer = context.origin;
    }
    return outer;
}

void Interpreter::fail(Span span, std::string message) {
    diagnostics_.error(sources_, at(span), std::move(message));
    throw EvaluationError{};
}

void Interpreter::stop(Span span, std::string message) {
    diagnostics_.error(sources_, at(span), std::move(message));
    stopped_ = true;
    throw EvaluationStopped{};
}

void Interpreter::out_of_operations(Span span) {
    stop(span, "the scene runs more than " + std::to_string(limits_.max_operations) +
                   " operations (the limit: each statement run and each operation of an expression counts "
                   "one): a loop or a recursion doing more work than a scene needs?");
}

EvaluatedScene Interpreter::run(const SceneArguments& arguments) {
    const ParameterValues& parameters = arguments.parameters;
    frame_ = arguments.frame;
    compiler_.set_include_dirs(arguments.include_dirs);
    stack_top_ = TRACER_STACK_ADDRESS();
    // Step 1: the command line's parameters, each a value alone.
    for (const auto& [name, text] : parameters) {
        SourceFile file("-D " + name, text);
        Diagnostics problems;
        Expr expr;
        ExprCode node;
        Sources alone(std::make_unique<SourceFile>(file.path(), text));
        Interpreter machine(alone, problems, limits_, {});
        RuntimeValue value;
        bool ok =
            parse_single_expression(file, problems, expr) && machine.compiler_.compile_lone_value(expr, false, node);
        if (ok) {
            try {
                value = machine.evaluate(node);
            } catch (const EvaluationError&) {
                ok = false;
            } catch (const EvaluationStopped&) {
                ok = false;
            }
        }
        if (!ok) {
            const std::string why = problems.all().empty() ? "not a value" : problems.all().front().message;
            diagnostics_.report(Severity::Error, Diagnostics::whole_file("<command line>"),
                                "-D " + name + "=" + text + ": " + why);
            continue;
        }
        overrides_[name] = value;
        override_texts_[name] = text;
    }
    // Step 2: the scene file, statement by statement: parsed, compiled and run, then dropped
    // (functions keep their code), so that a big scene is never held whole.
    std::error_code unresolved;
    compiler_.set_scene_path(fs::weakly_canonical(fs::path(sources_.scene().path()), unresolved).string());
    StatementReader reader(sources_.scene(), diagnostics_, 0);
    std::vector<Statement> statements;
    std::vector<StatementCode> steps;
    while (!stopped_ && reader.next(statements)) {
        for (const Statement& statement : statements) compiler_.compile_top_level(statement, steps);
        statements.clear();
        stack_.resize(compiler_.top_level_slots());
        try {
            run_steps(steps);
        } catch (const EvaluationStopped&) {
        }
        if (keep_code_) kept_.push_back(std::move(steps));
        steps.clear();  // (moved from: valid, now also empty)
    }
    // Step 3: -D names the scene does not declare.
    for (const auto& [name, value] : overrides_) {
        bool declared = false;
        std::vector<std::string_view> params;
        for (const auto& [declared_name, slot] : compiler_.parameters()) {
            params.push_back(declared_name);
            declared = declared || declared_name == name;
        }
        if (declared) continue;
        diagnostics_.report(Severity::Error, Diagnostics::whole_file("<command line>"),
                            "-D " + name + ": the scene has no 'param " + name + "'" + did_you_mean(name, params));
    }
    scene_.names = compiler_.take_definitions();
    return std::move(scene_);
}

EvaluatedScene Interpreter::run_again(const FrameTime& frame, BlockSink on_block) {
    // Everything a run changes, as a new interpreter has it; the code and the -D values stay.
    scene_ = {};
    stack_.assign(compiler_.top_level_slots(), RuntimeValue{});
    frame_base_ = 0;
    running_ = {};
    step_failed_ = returned_value_ = stopped_ = false;
    returned_ = {};
    making_blocks_ = true;
    contexts_.clear();
    current_group_.reset();
    blocks_ = iterations_run_ = operations_ = list_items_ = call_depth_ = 0;
    frame_ = frame;
    on_block_ = std::move(on_block);
    stack_top_ = TRACER_STACK_ADDRESS();
    for (const std::vector<StatementCode>& steps : kept_) {
        if (stopped_) break;
        try {
            run_steps(steps);
        } catch (const EvaluationStopped&) {
        }
    }
    return std::move(scene_);
}

Interpreter::Flow Interpreter::run_steps(const std::vector<StatementCode>& steps) {
    for (const StatementCode& step : steps) {
        if (stopped_ || diagnostics_.saturated()) return Flow::Next;
        if (++operations_ > limits_.max_operations) out_of_operations(step.keyword);
        try {
            if (run_step(step) == Flow::Return) return Flow::Return;
        } catch (const EvaluationError&) {
            step_failed_ = true;
        }
    }
    return Flow::Next;
}

Interpreter::Flow Interpreter::run_step(const StatementCode& step) {
    switch (step.op) {
        case StatementCode::Op::Block: run_block(step); break;
        case StatementCode::Op::Let:
        case StatementCode::Op::Param: run_binding(step); break;
        case StatementCode::Op::Range: return run_range(step);
        case StatementCode::Op::Each: return run_each(step);
        case StatementCode::Op::While:
            // Each pass counts as a loop iteration: a condition that stays true meets the limit.
            while (count_iteration(step) && condition(step.value))
                if (run_steps(step.steps) == Flow::Return) return Flow::Return;
            break;
        case StatementCode::Op::If: return run_steps(condition(step.value) ? step.steps : step.otherwise);
        case StatementCode::Op::Function: {
            auto function = std::make_shared<FunctionObject>();
            function->code = step.function;
            for (const ExprCode& capture : step.function->captures) function->captures.push_back(evaluate(capture));
            RuntimeValue value;
            value.kind = RuntimeValue::Kind::Function;
            value.object = std::move(function);
            slot(step.slot) = std::move(value);
            break;
        }
        case StatementCode::Op::Return: try { returned_ = step.has_value ? evaluate(step.value) : RuntimeValue{};
            } catch (const EvaluationError&) {
                returned_ = RuntimeValue::broken();  // reported: the caller's use of it is not an error too
            }
            returned_value_ = step.has_value;  // after the value: computing it may call and return
            return Flow::Return;
        case StatementCode::Op::Call: call(step.value, false); break;
        case StatementCode::Op::Print: {
            const RuntimeValue values = evaluate(step.value);  // its errors reported, kept or not
            if (diagnostics_.prints_full()) {                  // only counted: no text, no location
                diagnostics_.printed({}, {});
                break;
            }
            std::string text;
            for (const RuntimeValue& value : values.items()) text += (text.empty() ? "" : " ") + value_text(value);
            diagnostics_.printed(Diagnostics::locate(sources_, at(step.keyword)), std::move(text));
            break;
        }
        case StatementCode::Op::Group: {
            bool failed = false;
            auto group = std::make_shared<Group>();
            group->kind = step.word;
            group->keyword = at(step.keyword);
            group->placement = std::move(*make_body(*step.body, failed));
            group->outer = current_group_;
            if (failed || step.broken) group->broken = true;
            std::shared_ptr<const Group> outer = std::move(current_group_);
            current_group_ = std::move(group);
            const size_t blocks_before = blocks_;
            const Flow flow = run_steps(step.steps);
            current_group_ = std::move(outer);
            if (step.word != "group" && blocks_ == blocks_before && !stopped_ && !failed && !step.broken &&
                !step.unclosed)
                diagnostics_.error(sources_, at(step.keyword),
                                   "this " + step.word + " holds no shapes: write its parts inside, e.g. " + step.word +
                                       " { box { ... } sphere { ... } }");
            return flow;
        }
        case StatementCode::Op::Include: return run_include(step);
    }
    return Flow::Next;
}

void Interpreter::run_block(const StatementCode& step) {
    if (!making_blocks_)
        fail(step.keyword, "a function called for its value makes no blocks: call '" + running_.function().code->name +
                               "(...)' alone, as a statement, for its blocks");
    if (++blocks_ > limits_.max_blocks) {
        diagnostics_.error(sources_, at(step.keyword),
                           "the scene generates more than " + std::to_string(limits_.max_blocks) +
                               " blocks (the limit); generate fewer");
        stopped_ = true;
        return;
    }
    // The contexts' origins made for this block alone are forgotten after it, unless a message
    // or the validator kept one of its spans: a loop of a million blocks then holds none.
    const size_t origins_before = sources_.origins();
    const int reported_before = diagnostics_.error_count() + diagnostics_.warning_count();
    Block block;
    block.kind = step.word;
    block.spec = step.body->spec;
    block.kind_span = at(step.keyword);
    block.name = step.name;
    block.name_span = at(step.name_span);
    bool failed = false;
    fill_body(*step.body, block.body, failed);
    block.broken = step.broken;  // a syntax error: not validated too (broken entries are)
    block.group = current_group_;
    if (!on_block_) return scene_.blocks.push_back(std::move(block));
    const bool kept = on_block_(std::move(block));
    if (kept || diagnostics_.error_count() + diagnostics_.warning_count() != reported_before) return;
    sources_.forget_origins_from(origins_before);
    for (RunContext& context : contexts_)
        if (context.has_origin && context.origin >= origins_before) context.has_origin = false;
}

// A body's entries evaluated; `failed` is set if a value had an error (reported).
std::shared_ptr<Body> Interpreter::make_body(const CompiledBody& code, bool& failed) {
    auto body = std::make_shared<Body>();
    fill_body(code, *body, failed);
    return body;
}

void Interpreter::fill_body(const CompiledBody& code, Body& filled, bool& failed) {
    Body* body = &filled;
    body->open_brace = at(code.open_brace);
    body->close_brace = at(code.close_brace);
    body->entries.reserve(code.entries.size());
    for (const CompiledEntry& entry : code.entries) {
        Entry out;
        out.key = entry.key;
        out.key_span = at(entry.key_span);
        out.spec = entry.spec;
        if (entry.nested) {
            out.value.kind = PlainValue::Kind::Block;
            out.value.span = {entry.body->open_brace.begin, entry.body->close_brace.end, here()};
            out.value.body = make_body(*entry.body, failed);
        } else {
            bool ok = false;
            try {
                ok = entry_value(entry, out.value);
            } catch (const EvaluationError&) {
            }
            if (!ok) {  // reported; kept so that the rest of the block is still checked
                failed = true;
                out.value = PlainValue{};
                out.value.kind = PlainValue::Kind::Broken;
                out.value.span = at(entry.value.span);
            }
        }
        body->entries.push_back(std::move(out));
    }
}

void Interpreter::run_binding(const StatementCode& step) {
    RuntimeValue value = evaluate(step.value);
    if (step.op == StatementCode::Op::Param) {
        if (auto given = overrides_.find(step.name); given != overrides_.end()) {
            value = given->second;
            command_line_[step.slot] = "-D " + step.name + "=" + override_texts_[step.name];
        }
        scene_.parameters.emplace_back(step.name, PlainValue{});
        plain_value(value, at(step.value.span), scene_.parameters.back().second);
    }
    slot(step.slot) = std::move(value);
}

// Counts one more iteration of `step`'s loop: false (reported, and everything stopped) past the limit.
bool Interpreter::count_iteration(const StatementCode& step) {
    if (stopped_ || diagnostics_.saturated()) return false;
    if (++iterations_run_ <= limits_.max_iterations) return true;
    diagnostics_.error(
        sources_, at(step.keyword),
        "the scene runs more than " + std::to_string(limits_.max_iterations) + " loop iterations (the limit)");
    stopped_ = true;
    return false;
}

Interpreter::Flow Interpreter::run_range(const StatementCode& step) {
    const double first = number_operand(evaluate(step.value), step.value.span, "the first number of a range");
    const double end = number_operand(evaluate(step.end), step.end.span, "the end of a range");
    for (const ExprCode* bound : {&step.value, &step.end}) {
        const double value = bound == &step.value ? first : end;
        if (std::floor(value) != value)
            fail(bound->span, "a range goes from whole number to whole number; this is " + format_number(value));
    }
    if (end <= first) {
        // Outside other loops only: inside one, a range empty in some iterations is common
        // (for j in 0..i) and meant.
        if (!step.top_level || !contexts_.empty()) return Flow::Next;
        const Span range{step.value.span.begin, step.end.span.end, step.value.span.origin};
        diagnostics_.warning(sources_, at(range),
                             "this loop runs no iterations: " + format_number(first) + ".." + format_number(end) +
                                 " is empty (a range A..B counts up, from A to B - 1)");
        return Flow::Next;
    }
    // The name as the source text holds it: the iterations' notes are written later.
    const std::string_view name = sources_.file(step.name_span).slice(step.name_span);
    for (double i = first; i < end; ++i) {
        if (!count_iteration(step)) return Flow::Next;
        slot(step.slot) = RuntimeValue::number(i);
        contexts_.push_back({RunContext::Kind::Iteration, step.keyword, name, i});
        const Flow flow = run_steps(step.steps);
        contexts_.pop_back();
        if (flow == Flow::Return) return flow;
    }
    return Flow::Next;
}

Interpreter::Flow Interpreter::run_each(const StatementCode& step) {
    const RuntimeValue list = evaluate(step.value);
    if (list.kind != RuntimeValue::Kind::List)
        fail(step.value.span, "'for " + step.name + " in' takes a range A..B or a list; this is " + runtime_kind(list));
    const std::vector<RuntimeValue>& items = list.items();
    for (size_t i = 0; i < items.size(); ++i) {
        if (!count_iteration(step)) return Flow::Next;
        slot(step.slot) = items[i];
        contexts_.push_back({RunContext::Kind::Iteration, step.keyword, {}, double(i)});
        const Flow flow = run_steps(step.steps);
        contexts_.pop_back();
        if (flow == Flow::Return) return flow;
    }
    return Flow::Next;
}

// An include run: its file's code, in place; at the top of the scene its spans keep the origin
// they were compiled with, inside a loop or call each run gets one of its own.
Interpreter::Flow Interpreter::run_include(const StatementCode& step) {
    RunContext context{RunContext::Kind::Include, step.name_span, {}, 0, step.origin};
    if (contexts_.empty() || (contexts_.back().kind == RunContext::Kind::Include &&
                              contexts_.back().origin == step.name_span.origin && contexts_.back().has_origin)) {
        context.origin = step.origin;
        context.has_origin = true;
    }
    contexts_.push_back(context);
    const Flow flow = run_steps(step.steps);
    contexts_.pop_back();
    return flow;
}

bool Interpreter::single_value(const Expr& expr, PlainValue& out) {
    try {
        if (expr.kind == Expr::Kind::Block && expr.text.empty()) {
            out.kind = PlainValue::Kind::Block;
            out.span = expr.span;
            bool failed = false;
            const auto code = compiler_.compile_lone_block(*expr.body, failed);
            out.body = make_body(*code, failed);
            return !failed;
        }
        ExprCode node;
        if (!compiler_.compile_lone_value(expr, true, node)) return false;
        CompiledEntry entry;
        entry.value = std::move(node);
        return entry_value(entry, out);
    } catch (const EvaluationError&) {
        return false;
    } catch (const EvaluationStopped&) {
        return false;
    }
}

EvaluatedScene interpret(Sources& sources, Diagnostics& diagnostics, const SceneArguments& arguments,
                         const InterpretLimits& limits, const BlockSink& on_block) {
    EvaluatedScene scene;
    // On a stack of its own, large enough for calls nested as deep as the limit allows.
    run_on_big_stack([&] {
        Interpreter interpreter(sources, diagnostics, limits, on_block);
        scene = interpreter.run(arguments);
    });
    return scene;
}

bool evaluate_single_value(const SourceFile& file, Diagnostics& diagnostics, PlainValue& out) {
    Expr expr;
    if (!parse_single_expression(file, diagnostics, expr)) return false;
    Sources sources(std::make_unique<SourceFile>(file.path(), std::string(file.text())));
    return Interpreter(sources, diagnostics, {}, {}).single_value(expr, out);
}

}  // namespace tracer
