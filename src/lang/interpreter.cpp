#include "lang/interpreter.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <set>

#include "base/input_file.h"
#include "lang/builtins.h"
#include "lang/parser.h"
#include "lang/schema.h"
#include "lang/suggest.h"

namespace tracer {
namespace {

namespace fs = std::filesystem;

// Thrown after an error inside an expression has been reported: the entry is dropped.
struct EvaluationError {};

// What a name holds, and where it was defined. A name whose value had an error is `broken`:
// using it is an error already reported.
struct Binding {
    Value value;
    Span defined_at;
    bool broken = false;
};

// A loop iteration not yet given an origin: it gets one only when something made in it needs a
// span (most iterations of a big loop make blocks, but a bare `let` loop makes none).
struct Iteration {
    Span loop;
    std::string_view name;
    double value = 0;
    uint32_t origin = 0;
    bool has_origin = false;
};

class Interpreter {
public:
    Interpreter(Sources& sources, Diagnostics& diagnostics, const InterpretLimits& limits = {}, BlockSink on_block = {})
        : sources_(sources), diagnostics_(diagnostics), limits_(limits), on_block_(std::move(on_block)) {}

    EvaluatedScene run(const ParameterValues& parameters);
    bool single_value(const Expr& expr, Value& out);

private:
    // Statements.
    void run_file(const SourceFile& file, uint32_t origin);
    void run_statements(const std::vector<Statement>& statements, uint32_t origin);
    void run_block(const Statement& statement, uint32_t origin);
    void run_binding(const Statement& statement, uint32_t origin);
    void run_loop(const Statement& statement, uint32_t origin);
    void run_include(const Statement& statement, uint32_t origin);
    std::shared_ptr<Body> run_body(const BodyCode& code, const BlockSpec* spec, uint32_t origin, bool& failed);

    // Expressions.
    // `top`: the whole value of an entry, where an unknown name is a word (`accel sah`);
    // `word_key`: the entry's key takes a word (a material name, a choice), which then comes
    // before a built-in constant of the same name.
    Value evaluate(const Expr& expr, uint32_t origin, bool top = false, bool word_key = false);
    Value evaluate_name(const Expr& expr, uint32_t origin, bool top, bool word_key);
    Value evaluate_binary(const Expr& expr, uint32_t origin);
    // a `operation` b, the result spanning `span`.
    Value apply_binary(char operation, const Value& a, const Value& b, Span span);
    Value evaluate_call(const Expr& expr, uint32_t origin);
    Value evaluate_component(const Expr& expr, uint32_t origin);
    Value finite(Value value, Span at);
    [[noreturn]] void fail(Span at, std::string message);
    double number_operand(const Value& value, const std::string& what);

    // Names.
    const Binding* find(const std::string& name) const;
    std::vector<std::string_view> names_in_scope() const;
    void bind(const std::string& name, Binding binding);

    // Origins: which file, include and loop iteration a span belongs to.
    uint32_t here(uint32_t origin);
    Span at(Span span, uint32_t origin) { return {span.begin, span.end, here(origin)}; }

    Sources& sources_;
    Diagnostics& diagnostics_;
    EvaluatedScene scene_;
    std::vector<std::map<std::string, Binding, std::less<>>> scopes_{1};
    std::map<std::string, Value, std::less<>> overrides_;  // -D values, by name
    std::set<std::string, std::less<>> used_overrides_;
    std::vector<Iteration> iterations_;  // the loops being run, innermost last
    std::vector<std::string> include_stack_;
    std::map<std::string, uint32_t> included_;  // each file read, by canonical path: its first origin
    size_t included_bytes_ = 0;                 // text run through includes, repeats counted
    size_t blocks_ = 0, iterations_run_ = 0;
    bool stopped_ = false;  // a limit was hit: nothing more is generated
    InterpretLimits limits_;
    BlockSink on_block_;
};

// The origin for spans evaluated now: the innermost iteration's (created on first use) or else
// the file's own.
uint32_t Interpreter::here(uint32_t origin) {
    if (iterations_.empty()) return origin;
    Iteration& iteration = iterations_.back();
    if (!iteration.has_origin) {
        // Outer iterations first: the loop's own span lies in the iteration around it.
        Span loop = iteration.loop;
        if (iterations_.size() > 1) {
            Iteration saved = iterations_.back();
            iterations_.pop_back();
            loop.origin = here(loop.origin);
            iterations_.push_back(saved);
        }
        iterations_.back().origin = sources_.add_iteration(loop, iteration.name, iteration.value);
        iterations_.back().has_origin = true;
    }
    return iterations_.back().origin;
}

void Interpreter::fail(Span span, std::string message) {
    diagnostics_.error(sources_, span, std::move(message));
    throw EvaluationError{};
}

EvaluatedScene Interpreter::run(const ParameterValues& parameters) {
    // Step 1: the command line's parameters, each a value alone.
    for (const auto& [name, text] : parameters) {
        SourceFile file("-D " + name, text);
        Diagnostics problems;
        Value value;
        if (!evaluate_single_value(file, problems, value)) {
            const std::string why = problems.all().empty() ? "not a value" : problems.all().front().message;
            diagnostics_.report(Severity::Error, Diagnostics::whole_file("<command line>"),
                                "-D " + name + "=" + text + ": " + why);
            continue;
        }
        overrides_[name] = value;
    }
    // Step 2: the scene file, statement by statement (on the include stack itself, so that a
    // scene including itself is caught at that include, before its blocks are run again).
    std::error_code unresolved;
    include_stack_.push_back(fs::weakly_canonical(fs::path(sources_.scene().path()), unresolved).string());
    run_file(sources_.scene(), 0);
    include_stack_.pop_back();
    // Step 3: -D names the scene does not declare.
    for (const auto& [name, value] : overrides_) {
        if (used_overrides_.count(name)) continue;
        std::vector<std::string_view> params;
        for (const auto& [declared, ignored] : scene_.parameters) params.push_back(declared);
        diagnostics_.report(Severity::Error, Diagnostics::whole_file("<command line>"),
                            "-D " + name + ": the scene has no 'param " + name + "'" + did_you_mean(name, params));
    }
    return std::move(scene_);
}

// A file read and run one statement at a time: only the scene it makes is held whole.
void Interpreter::run_file(const SourceFile& file, uint32_t origin) {
    StatementReader reader(file, diagnostics_, origin);
    std::vector<Statement> statement;
    while (!stopped_ && reader.next(statement)) {
        run_statements(statement, origin);
        statement.clear();
    }
}

void Interpreter::run_statements(const std::vector<Statement>& statements, uint32_t origin) {
    for (const Statement& statement : statements) {
        if (stopped_ || diagnostics_.saturated()) return;
        switch (statement.kind) {
            case Statement::Kind::Block: run_block(statement, origin); break;
            case Statement::Kind::Let:
            case Statement::Kind::Param: run_binding(statement, origin); break;
            case Statement::Kind::For: run_loop(statement, origin); break;
            case Statement::Kind::Include: run_include(statement, origin); break;
        }
    }
}

void Interpreter::run_block(const Statement& statement, uint32_t origin) {
    if (++blocks_ > limits_.max_blocks) {
        diagnostics_.error(sources_, at(statement.keyword, origin),
                           "the scene generates more than " + std::to_string(limits_.max_blocks) +
                               " blocks (the limit); generate fewer");
        stopped_ = true;
        return;
    }
    Block block;
    block.kind = statement.word;
    block.kind_span = at(statement.keyword, origin);
    block.name = statement.name;
    block.name_span = at(statement.name_span, origin);
    bool failed = false;
    block.body = std::move(*run_body(statement.body, find_block_spec(statement.word), origin, failed));
    block.broken = statement.broken || failed;  // reported: not validated too
    if (on_block_)
        on_block_(std::move(block));
    else
        scene_.blocks.push_back(std::move(block));
}

// A body's entries evaluated, their keys looked up in `spec` (the block's table; none for an
// unknown block); `failed` is set if a value had an error (reported).
std::shared_ptr<Body> Interpreter::run_body(const BodyCode& code, const BlockSpec* spec, uint32_t origin,
                                            bool& failed) {
    auto body = std::make_shared<Body>();
    body->open_brace = at(code.open_brace, origin);
    body->close_brace = at(code.close_brace, origin);
    for (const EntryCode& entry : code.entries) {
        const KeySpec* key = spec ? spec->find_key(entry.key) : nullptr;
        Entry out;
        out.key = entry.key;
        out.key_span = at(entry.key_span, origin);
        if (entry.value.kind == Expr::Kind::Block) {
            // A nested block: its own table (rotate, transform), or a material's.
            const BlockSpec* nested = key && key->block                            ? key->block
                                      : key && key->type == ValueType::MaterialRef ? find_block_spec("material")
                                                                                   : nullptr;
            out.value.kind = Value::Kind::Block;
            out.value.span = at(entry.value.span, origin);
            out.value.body = run_body(*entry.value.body, nested, origin, failed);
        } else {
            try {
                if (key && key->type == ValueType::Path && entry.value.kind != Expr::Kind::String) {
                    const Span span = at(entry.value.span, origin);
                    fail(span, "'" + entry.key + "' expects a file path in double quotes: " + entry.key + " \"" +
                                   std::string(sources_.file(span).slice(span)) + "\"");
                }
                const bool word_key = key && (key->type == ValueType::MaterialRef || key->type == ValueType::Choice);
                out.value = evaluate(entry.value, origin, true, word_key);
            } catch (const EvaluationError&) {
                failed = true;
                continue;
            }
        }
        body->entries.push_back(std::move(out));
    }
    return body;
}

void Interpreter::run_binding(const Statement& statement, uint32_t origin) {
    const bool param = statement.kind == Statement::Kind::Param;
    const Span name_span = at(statement.name_span, origin);
    Binding binding;
    binding.defined_at = name_span;
    try {
        binding.value = evaluate(statement.value, origin);
        if (binding.value.kind != Value::Kind::Number && binding.value.kind != Value::Kind::Vector)
            fail(binding.value.span, "a name holds a number or a vector; this is " + kind_of(binding.value));
    } catch (const EvaluationError&) {
        binding.broken = true;  // uses of it are not errors too
        bind(statement.name, std::move(binding));
        return;
    }
    if (param) {
        auto given = overrides_.find(statement.name);
        if (given != overrides_.end()) {
            used_overrides_.insert(statement.name);
            const Span span = binding.value.span;
            binding.value = given->second;
            binding.value.span = span;
            binding.value.component_spans.assign(binding.value.components.size(), span);
        }
        scene_.parameters.emplace_back(statement.name, binding.value);
    }
    bind(statement.name, std::move(binding));
}

// Binds in the innermost scope; a name already bound in that same scope is an error (a loop
// body's names shadow the file's).
void Interpreter::bind(const std::string& name, Binding binding) {
    auto& scope = scopes_.back();
    auto found = scope.find(name);
    if (found != scope.end()) {
        Diagnostic* d = diagnostics_.error(sources_, binding.defined_at, "'" + name + "' is already defined");
        Diagnostics::note(d, sources_, found->second.defined_at, "'" + name + "' was first defined here");
        return;
    }
    scope.emplace(name, std::move(binding));
}

void Interpreter::run_loop(const Statement& statement, uint32_t origin) {
    double first = 0, end = 0;
    try {
        first = number_operand(evaluate(statement.value, origin), "the first number of a range");
        end = number_operand(evaluate(statement.end, origin), "the end of a range");
        for (const Expr* bound : {&statement.value, &statement.end}) {
            const double value = bound == &statement.value ? first : end;
            if (std::floor(value) != value)
                fail(at(bound->span, origin),
                     "a range goes from whole number to whole number; this is " + format_number(value));
        }
    } catch (const EvaluationError&) {
        return;
    }
    if (end <= first) {
        // Outside other loops only: inside one, a range empty in some iterations is common
        // (for j in 0..i) and meant.
        if (!iterations_.empty()) return;
        const Span range{statement.value.span.begin, statement.end.span.end, statement.value.span.origin};
        diagnostics_.warning(sources_, at(range, origin),
                             "this loop runs no iterations: " + format_number(first) + ".." + format_number(end) +
                                 " is empty (a range A..B counts up, from A to B - 1)");
        return;
    }
    // The name as the source text holds it: the statement itself is gone once it has run, and
    // the iterations' notes are written later.
    const std::string_view name = sources_.file(at(statement.name_span, origin)).slice(statement.name_span);
    for (double i = first; i < end; ++i) {
        if (stopped_ || diagnostics_.saturated()) return;
        if (++iterations_run_ > limits_.max_iterations) {
            diagnostics_.error(
                sources_, at(statement.keyword, origin),
                "the scene runs more than " + std::to_string(limits_.max_iterations) + " loop iterations (the limit)");
            stopped_ = true;
            return;
        }
        iterations_.push_back({at(statement.keyword, origin), name, i});
        scopes_.emplace_back();
        Binding binding;
        binding.value = number_value(i, statement.name_span);
        binding.defined_at = at(statement.name_span, origin);
        scopes_.back().emplace(statement.name, std::move(binding));
        run_statements(statement.statements, origin);
        scopes_.pop_back();
        iterations_.pop_back();
    }
}

void Interpreter::run_include(const Statement& statement, uint32_t origin) {
    const Span path_span = at(statement.name_span, origin);
    const SourceFile& including = sources_.file(path_span);
    fs::path path = statement.word;
    if (path.is_relative()) path = fs::path(including.path()).parent_path() / path;
    std::error_code ignored;
    const std::string canonical = fs::weakly_canonical(path, ignored).string();
    if (std::find(include_stack_.begin(), include_stack_.end(), canonical) != include_stack_.end()) {
        diagnostics_.error(sources_, path_span, "'" + statement.word + "' includes itself (through the files noted)");
        return;
    }
    if (int(include_stack_.size()) > kMaxIncludeDepth) {  // the scene and 32 includes below it
        diagnostics_.error(sources_, path_span, "includes are nested too deeply (more than 32 files)");
        return;
    }
    // Each file is read once; a file included again (by a loop, say) is run from the text held.
    uint32_t file_origin = 0;
    if (auto known = included_.find(canonical); known != included_.end()) {
        file_origin = sources_.add_include_again(known->second, path_span);
    } else {
        InputFile input = read_input_file(path.string(), kMaxSceneFileBytes);
        if (!input.problem.empty()) {
            diagnostics_.error(sources_, path_span,
                               "cannot include '" + path.lexically_normal().string() + "': " + input.problem);
            return;
        }
        file_origin = sources_.add_include(
            std::make_unique<SourceFile>(path.lexically_normal().string(), std::move(input.text)), path_span);
        included_.emplace(canonical, file_origin);
    }
    const SourceFile& file = sources_.file({0, 0, file_origin});
    included_bytes_ += file.text().size();
    if (included_bytes_ > kMaxIncludedBytes) {
        diagnostics_.error(sources_, path_span,
                           "the scene includes more than 256 MiB of text in all (each inclusion counted; the limit)");
        stopped_ = true;
        return;
    }
    include_stack_.push_back(canonical);
    std::vector<Iteration> outer;  // the included file's spans carry its own origin
    std::swap(outer, iterations_);
    run_file(file, file_origin);
    std::swap(outer, iterations_);
    include_stack_.pop_back();
}

const Binding* Interpreter::find(const std::string& name) const {
    for (auto scope = scopes_.rbegin(); scope != scopes_.rend(); ++scope) {
        auto found = scope->find(name);
        if (found != scope->end()) return &found->second;
    }
    return nullptr;
}

std::vector<std::string_view> Interpreter::names_in_scope() const {
    std::vector<std::string_view> names;
    for (const auto& scope : scopes_)
        for (const auto& [name, binding] : scope) names.push_back(name);
    return names;
}

// Non-finite results (1e300 * 1e300, 0 * huge / tiny) are errors where they happen.
Value Interpreter::finite(Value value, Span span) {
    bool ok = is_number(value) ? std::isfinite(value.number) : true;
    for (double c : value.components) ok = ok && std::isfinite(c);
    if (!ok) fail(span, "this expression's value is not finite (too large for a double)");
    return value;
}

double Interpreter::number_operand(const Value& value, const std::string& what) {
    if (!is_number(value)) fail(value.span, what + " must be a number; this is " + kind_of(value));
    return value.number;
}

Value Interpreter::evaluate(const Expr& expr, uint32_t origin, bool top, bool word_key) {
    const Span span = at(expr.span, origin);
    switch (expr.kind) {
        case Expr::Kind::Number: return number_value(expr.number, span);
        case Expr::Kind::String: {
            Value value;
            value.kind = Value::Kind::String;
            value.text = expr.text;
            value.span = span;
            return value;
        }
        case Expr::Kind::Name: return evaluate_name(expr, origin, top, word_key);
        case Expr::Kind::Vector: {
            Value value;
            value.kind = Value::Kind::Vector;
            value.span = span;
            for (const Expr& component : expr.operands) {
                const Value part = evaluate(component, origin);
                value.components.push_back(number_operand(part, "a vector's component"));
                value.component_spans.push_back(part.span);
            }
            return value;
        }
        case Expr::Kind::Unary: {
            Value value = evaluate(expr.operands[0], origin);
            if (!is_number(value) && !is_vector(value))
                fail(value.span,
                     std::string("'") + expr.op + "' applies to numbers and vectors; this is " + kind_of(value));
            if (expr.op == '-') {
                value.number = -value.number;
                for (double& c : value.components) c = -c;
            }
            value.span = span;
            if (is_vector(value)) value.component_spans.assign(value.components.size(), span);
            return value;
        }
        case Expr::Kind::Binary: return evaluate_binary(expr, origin);
        case Expr::Kind::Call: return evaluate_call(expr, origin);
        case Expr::Kind::Component: return evaluate_component(expr, origin);
        case Expr::Kind::Block: fail(span, "a block { ... } is not a value here");
    }
    fail(span, "not a value");
}

// A bound name gives its value (at this span); an unbound one at the top of an entry is a word
// for the validator (a material, `sah`, `true`), unless it is close to a name in scope, which
// makes it a misspelled name.
Value Interpreter::evaluate_name(const Expr& expr, uint32_t origin, bool top, bool word_key) {
    const Span span = at(expr.span, origin);
    if (const Binding* binding = find(expr.text)) {
        if (binding->broken) throw EvaluationError{};  // its definition's error is reported
        Value value = binding->value;
        value.span = span;
        value.component_spans.assign(value.components.size(), span);
        return value;
    }
    const BuiltinConstant* constant = word_key ? nullptr : find_constant(expr.text);
    if (constant) return number_value(constant->value, span);
    const std::string suggestion =
        scopes_.size() == 1 && scopes_[0].empty() ? "" : did_you_mean(expr.text, names_in_scope());
    if (top && (names_nan_or_infinity(expr.text) || suggestion.empty())) {
        Value word;
        word.kind = Value::Kind::Identifier;
        word.text = expr.text;
        word.span = span;
        return word;
    }
    if (names_nan_or_infinity(expr.text))
        fail(span, "undefined name " + in_quotes(expr.text) + " (NaN and infinity are not allowed)");
    fail(span, "undefined name " + in_quotes(expr.text) + suggestion);
}

// A chain a + b - c * d ... is a tree as deep as it is long, on its left side: it is walked
// down that side iteratively and folded from the innermost operation out, so that no length of
// chain can exhaust the native stack (right operands are bounded by the parentheses' limit).
Value Interpreter::evaluate_binary(const Expr& expr, uint32_t origin) {
    // The operations down the left side, outermost first: on the native stack for the few a
    // written expression has (no allocation per evaluation), on the heap past that.
    const Expr* chain_on_stack[16];
    std::vector<const Expr*> chain_on_heap;
    size_t length = 0;
    const Expr* leftmost = &expr;
    for (; leftmost->kind == Expr::Kind::Binary; leftmost = &leftmost->operands[0], ++length) {
        if (length == std::size(chain_on_stack))
            chain_on_heap.assign(std::begin(chain_on_stack), std::end(chain_on_stack));
        if (length < std::size(chain_on_stack))
            chain_on_stack[length] = leftmost;
        else
            chain_on_heap.push_back(leftmost);
    }
    const Expr* const* chain = length <= std::size(chain_on_stack) ? chain_on_stack : chain_on_heap.data();
    Value result = evaluate(*leftmost, origin);
    for (size_t k = length; k-- > 0;) {
        const Expr& e = *chain[k];
        result = apply_binary(e.op, result, evaluate(e.operands[1], origin), at(e.span, origin));
    }
    return result;
}

Value Interpreter::apply_binary(char operation, const Value& a, const Value& b, Span span) {
    const std::string op = std::string("'") + operation + "'";
    for (const Value* operand : {&a, &b})
        if (!is_number(*operand) && !is_vector(*operand))
            fail(operand->span, op + " applies to numbers and vectors; this is " + kind_of(*operand));
    if (is_number(a) && is_number(b)) {
        if (operation == '/' && b.number == 0) fail(b.span, "division by zero");
        const double x = a.number, y = b.number;
        const double result = operation == '+' ? x + y : operation == '-' ? x - y : operation == '*' ? x * y : x / y;
        return finite(number_value(result, span), span);
    }
    std::vector<double> out;
    if (is_vector(a) && is_vector(b)) {
        if (operation == '*' || operation == '/')
            fail(span, op + " does not multiply two vectors; use dot(a, b) or cross(a, b)");
        if (a.components.size() != b.components.size())
            fail(span, "the vectors have " + std::to_string(a.components.size()) + " and " +
                           std::to_string(b.components.size()) + " components");
        for (size_t i = 0; i < a.components.size(); ++i)
            out.push_back(operation == '+' ? a.components[i] + b.components[i] : a.components[i] - b.components[i]);
        return finite(vector_value(out, span), span);
    }
    // A vector and a number: scaled (v * s, s * v, v / s); adding them is an error.
    if (operation == '+' || operation == '-')
        fail(span, op + " needs two numbers or two vectors; this is a number and a vector");
    const Value& vector = is_vector(a) ? a : b;
    const double scalar = is_vector(a) ? b.number : a.number;
    if (operation == '/' && is_number(a)) fail(span, "a number cannot be divided by a vector");
    if (operation == '/' && scalar == 0) fail(b.span, "division by zero");
    for (double c : vector.components) out.push_back(operation == '*' ? c * scalar : c / scalar);
    return finite(vector_value(out, span), span);
}

Value Interpreter::evaluate_call(const Expr& expr, uint32_t origin) {
    const Span span = at(expr.span, origin);
    std::vector<Value> args;
    for (const Expr& operand : expr.operands) args.push_back(evaluate(operand, origin));
    const Builtin* function = find_builtin(expr.text);
    if (!function) {
        std::vector<std::string_view> names;
        for (const Builtin& builtin : all_builtins()) names.push_back(builtin.name);
        fail(at(Span{expr.span.begin, expr.span.begin + uint32_t(expr.text.size()), expr.span.origin}, origin),
             "unknown function " + in_quotes(expr.text) + did_you_mean(expr.text, names));
    }
    if (args.size() != function->arity)
        fail(span, "'" + expr.text + "' takes " + std::to_string(function->arity) + " argument" +
                       (function->arity == 1 ? "" : "s") + ", found " + std::to_string(args.size()));
    try {
        return finite(function->body(BuiltinArguments(function->name, args), span), span);
    } catch (const BuiltinError& error) {
        fail(error.span, error.message);
    }
}

Value Interpreter::evaluate_component(const Expr& expr, uint32_t origin) {
    const Span span = at(expr.span, origin);
    const Value value = evaluate(expr.operands[0], origin);
    static const std::string_view kNames[] = {"x", "y", "z"};
    const auto found = std::find(std::begin(kNames), std::end(kNames), expr.text);
    if (found == std::end(kNames))
        fail(span, "a vector's components are x, y and z; found " + in_quotes(expr.text) +
                       did_you_mean(expr.text, {"x", "y", "z"}));
    const size_t index = size_t(found - std::begin(kNames));
    if (!is_vector(value) || value.components.size() <= index)
        fail(value.span, "'." + expr.text + "' needs a vector; this is " + kind_of(value));
    return number_value(value.components[index], span);
}

bool Interpreter::single_value(const Expr& expr, Value& out) {
    try {
        if (expr.kind == Expr::Kind::Block) {
            out.kind = Value::Kind::Block;
            out.span = expr.span;
            bool failed = false;
            out.body = run_body(*expr.body, nullptr, 0, failed);
            if (failed) return false;
        } else {
            out = evaluate(expr, 0, true);
        }
    } catch (const EvaluationError&) {
        return false;
    }
    return true;
}

}  // namespace

EvaluatedScene interpret(Sources& sources, Diagnostics& diagnostics, const ParameterValues& parameters,
                         const InterpretLimits& limits, const BlockSink& on_block) {
    return Interpreter(sources, diagnostics, limits, on_block).run(parameters);
}

bool evaluate_single_value(const SourceFile& file, Diagnostics& diagnostics, Value& out) {
    Expr expr;
    if (!parse_single_expression(file, diagnostics, expr)) return false;
    Sources sources(std::make_unique<SourceFile>(file.path(), std::string(file.text())));
    return Interpreter(sources, diagnostics).single_value(expr, out);
}

}  // namespace tracer
