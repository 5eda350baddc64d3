#include "lang/internal/compile.h"

#include <algorithm>
#include <filesystem>

#include "base/input_file.h"
#include "lang/internal/builtins.h"
#include "lang/internal/parser.h"
#include "lang/internal/suggest.h"
#include "lang/internal/take_apart.h"
#include "lang/schema.h"
#include "lang/standard_library.h"

namespace tracer {

namespace fs = std::filesystem;

ExprCode::~ExprCode() {
    take_apart(operands);
}

namespace {

ExprCode leaf(ExprCode::Op op, Span span, uint32_t index = 0) {
    ExprCode node;
    node.op = op;
    node.span = span;
    node.index = index;
    return node;
}

ExprCode constant(RuntimeValue value, Span span) {
    ExprCode node = leaf(ExprCode::Op::Constant, span);
    node.constant = std::move(value);
    return node;
}

}  // namespace

std::string path_expected(std::string_view key, std::string_view written) {
    return "'" + std::string(key) + "' expects a file path in double quotes: " + std::string(key) + " \"" +
           std::string(written) + "\"";
}

std::string arguments_expected(std::string_view function, size_t expected, size_t found) {
    return in_quotes(function) + " takes " + std::to_string(expected) + " argument" + (expected == 1 ? "" : "s") +
           ", found " + std::to_string(found);
}

Compiler::Compiler(Sources& sources, Diagnostics& diagnostics) : sources_(sources), diagnostics_(diagnostics) {
    functions_.emplace_back();
    functions_.back().scopes.emplace_back();
}

void Compiler::fail(Span span, std::string message) {
    diagnostics_.error(sources_, span, std::move(message));
    throw CompileError{};
}

// Whether an unbound name written as a key's whole value is a word for the validator (a
// material, `sah`, `true`, `inf` to be refused by name) rather than an undefined name.
static bool may_be_word(const KeySpec* key, const Expr& value) {
    if (!key || value.kind != Expr::Kind::Name) return true;
    switch (key->type) {
        case ValueType::Number:
        case ValueType::Integer:
        case ValueType::Vector:
        case ValueType::Triple:
        case ValueType::Paint:
        case ValueType::ColorMap:
            return value.text == "true" || value.text == "false" || names_nan_or_infinity(value.text);
        default: return true;
    }
}

// Whether `value` is one of a choice key's own words: read as that word whatever names the scene
// has (`encoding srgb` where std/colors.scn defines a function srgb).
static bool is_choice_word(const KeySpec* key, const Expr& value) {
    return key && key->type == ValueType::Choice && value.kind == Expr::Kind::Name &&
           std::find(key->choices.begin(), key->choices.end(), value.text) != key->choices.end();
}

// A word as a key's value, read by the validator.
static ExprCode word(const Expr& value) {
    ExprCode node;
    node.op = ExprCode::Op::Word;
    node.span = value.span;
    node.text = value.text;
    return node;
}

void Compiler::compile_top_level(const Statement& statement, std::vector<StatementCode>& out) {
    compile_statement(statement, out);
}

bool Compiler::compile_lone_value(const Expr& expr, bool top, ExprCode& out) {
    try {
        out = compile_expression(expr, top);
    } catch (const CompileError&) {
        return false;
    }
    return true;
}

void Compiler::compile_statements(const std::vector<Statement>& statements, std::vector<StatementCode>& out) {
    for (const Statement& statement : statements) {
        if (diagnostics_.saturated()) return;
        compile_statement(statement, out);
    }
}

void Compiler::open_scope() {
    functions_.back().scopes.emplace_back();
}

void Compiler::close_scope() {
    FunctionLevel& level = functions_.back();
    // A `let` never read that hides a name of the blocks around it: most often meant to change
    // that name (`let total = total + i` in a loop leaves the outer total as it was).
    for (const auto& [name, info] : level.scopes.back()) {
        if (!info.from_let || info.read || info.assigned) continue;
        for (size_t s = level.scopes.size() - 1; s-- > 0;) {
            const auto outer = level.scopes[s].find(name);
            if (outer == level.scopes[s].end()) continue;
            Diagnostic* d = diagnostics_.warning(
                sources_, info.defined_at,
                "this makes a new '" + name + "' inside these braces, and nothing reads it; the outer '" + name +
                    "' is not changed: to change it, write '" + name + " = ...' (without 'let')");
            Diagnostics::note(d, sources_, outer->second.defined_at, "the outer '" + name + "' is defined here");
            break;
        }
    }
    level.next_slot -= uint32_t(level.scopes.back().size());  // the scope's slots are free again
    level.scopes.pop_back();
}

void Compiler::compile_scoped(const std::vector<Statement>& statements, std::vector<StatementCode>& out) {
    open_scope();
    compile_statements(statements, out);
    close_scope();
}

// Keeps where `name` is defined, for editors.
void Compiler::record(const std::string& name, Span defined_at, std::string_view kind) {
    if (definitions_.size() < kMostNamesRecorded) definitions_.push_back({name, kind, defined_at});
}

// Binds `name` in the innermost scope to a new slot; a name already bound in that same scope is
// an error (reported), and the old slot is kept.
uint32_t Compiler::bind(const std::string& name, Span defined_at, std::string_view kind) {
    record(name, defined_at, kind);
    FunctionLevel& level = functions_.back();
    Scope& scope = level.scopes.back();
    if (auto found = scope.find(name); found != scope.end()) {
        Diagnostic* d = diagnostics_.error(sources_, defined_at, "'" + name + "' is already defined");
        Diagnostics::note(d, sources_, found->second.defined_at, "'" + name + "' was first defined here");
        return found->second.slot;
    }
    const uint32_t slot = level.next_slot++;
    level.most_slots = std::max(level.most_slots, level.next_slot);
    NameInfo info{slot, defined_at, kind == "let"};
    info.shape_value = kind == "shape";
    info.function = kind == "fn";
    scope.emplace(name, info);
    return slot;
}

// The slot an assignment `name = value` writes: the name's, defined before in this function (or
// at the file's level, outside functions). Throws CompileError (reported) otherwise.
uint32_t Compiler::assigned_slot(const Statement& statement) {
    const std::string& name = statement.name;
    FunctionLevel& here = functions_.back();
    for (size_t s = here.scopes.size(); s-- > 0;) {
        auto found = here.scopes[s].find(name);
        if (found == here.scopes[s].end()) continue;
        found->second.assigned = true;
        return found->second.slot;
    }
    ExprCode outer;
    if (functions_.size() > 1 && resolve(name, functions_.size() - 2, statement.name_span, outer))
        fail(statement.name_span, "'" + name +
                                      "' is defined outside this function, which sees it as it was when the function "
                                      "was defined and cannot change it; return a value instead");
    fail(statement.name_span, "'" + name + "' is not defined yet: 'let " + name +
                                  " = ...' defines it, and 'name = ...' changes a name defined before" +
                                  did_you_mean(name, names_in_scope()));
}

// The node that reads `name` from the code at `level`: a slot of its frame, a global, the
// function itself, or a value captured from the levels around it (captured on first use).
bool Compiler::resolve(const std::string& name, size_t level, Span span, ExprCode& out) {
    FunctionLevel& here = functions_[level];
    for (size_t s = here.scopes.size(); s-- > 0;) {
        auto found = here.scopes[s].find(name);
        if (found == here.scopes[s].end()) continue;
        found->second.read = true;
        out = leaf(level == 0 && s == 0 ? ExprCode::Op::Global : ExprCode::Op::Local, span, found->second.slot);
        return true;
    }
    if (level == 0) return false;
    if (here.code->name == name) {
        out = leaf(ExprCode::Op::Self, span);
        return true;
    }
    if (auto known = here.capture_index.find(name); known != here.capture_index.end()) {
        out = leaf(ExprCode::Op::Capture, span, known->second);
        return true;
    }
    // The file's own names too are captured (not read when called): a function sees every name
    // as it was when the function was defined, whatever assignments come after.
    ExprCode outer;
    if (!resolve(name, level - 1, span, outer)) return false;
    const uint32_t index = uint32_t(here.code->captures.size());
    here.code->captures.push_back(std::move(outer));
    here.capture_index.emplace(name, index);
    out = leaf(ExprCode::Op::Capture, span, index);
    return true;
}

std::vector<std::string_view> Compiler::names_in_scope() const {
    std::vector<std::string_view> names;
    for (const FunctionLevel& level : functions_)
        for (const Scope& scope : level.scopes)
            for (const auto& [name, info] : scope) names.push_back(name);
    return names;
}

// A call of `print` (unless the scene defines a name print of its own).
bool Compiler::is_print(const Expr& call) {
    ExprCode ignored;
    return call.kind == Expr::Kind::Call && call.text == "print" &&
           !resolve("print", functions_.size() - 1, call.span, ignored);
}

// A call on a line of its own: print(...), or a function run for the blocks it makes. False if
// it is refused (reported).
bool Compiler::compile_call_statement(const Statement& statement, StatementCode& step) {
    if (is_print(statement.value)) {
        step.op = StatementCode::Op::Print;
        step.value = leaf(ExprCode::Op::List, statement.value.span);
        for (const Expr& argument : statement.value.operands)
            step.value.operands.push_back(compile_or_broken(argument));
        return true;
    }
    step.op = StatementCode::Op::Call;
    try {
        if (statement.shape_value) check_placed_value(statement.value);
        step.value = compile_expression(statement.value);
        if (step.value.op == ExprCode::Op::Builtin)
            fail(statement.value.span, "'" + statement.value.text +
                                           "' is a built-in function: it gives a value and makes no blocks; use its "
                                           "value, as in 'let x = " +
                                           statement.value.text + "(...)'");
    } catch (const CompileError&) {
        return false;
    }
    return true;
}

// A name alone on its line must name a shape value (let NAME = sphere { ... }); throws
// CompileError (reported) otherwise.
void Compiler::check_placed_value(const Expr& name) {
    for (size_t level = functions_.size(); level-- > 0;)
        for (size_t s = functions_[level].scopes.size(); s-- > 0;) {
            const auto found = functions_[level].scopes[s].find(name.text);
            if (found == functions_[level].scopes[s].end()) continue;
            if (found->second.shape_value) return;
            if (found->second.function)
                fail(name.span,
                     in_quotes(name.text) + " is a function: call it with its arguments, " + name.text + "(...)");
            fail(name.span, in_quotes(name.text) +
                                " is a value, which does nothing alone: a name alone on its line places a shape "
                                "value, made by 'let NAME = sphere { ... }' (or a group's or a solid's block)");
        }
    std::vector<std::string_view> names = names_in_scope();
    for (const BlockSpec* spec : all_block_specs())
        if (spec->top_level) names.push_back(spec->kind);
    const std::string suggestion = did_you_mean(name.text, names);
    fail(name.span, "undefined name " + in_quotes(name.text) +
                        (suggestion.empty() ? ": a name alone on its line places a shape value (let " + name.text +
                                                  " = sphere { ... })"
                                            : suggestion));
}

// `expr` compiled, or (its error reported) a broken value, whose uses are not errors too.
ExprCode Compiler::compile_or_broken(const Expr& expr) {
    try {
        return compile_expression(expr);
    } catch (const CompileError&) {
        return constant(RuntimeValue::broken(), expr.span);
    }
}

void Compiler::compile_statement(const Statement& statement, std::vector<StatementCode>& out) {
    StatementCode step;
    step.keyword = statement.keyword;
    step.name = statement.name;
    step.name_span = statement.name_span;
    step.word = statement.word;
    switch (statement.kind) {
        case Statement::Kind::Block: {
            step.op = StatementCode::Op::Block;
            step.broken = statement.broken;
            if (statement.word == "material" && !statement.name.empty())
                record(statement.name, statement.name_span, "material");
            bool failed = false;
            step.body = compile_body(statement.body, statement.word, find_block_spec(statement.word), failed);
            break;  // entries that failed to compile are kept broken: the block is still checked
        }
        case Statement::Kind::Let:
        case Statement::Kind::Param: {
            step.op = statement.kind == Statement::Kind::Let ? StatementCode::Op::Let : StatementCode::Op::Param;
            step.value = compile_or_broken(statement.value);
            step.slot = bind(statement.name, statement.name_span, step.op == StatementCode::Op::Let ? "let" : "param");
            if (step.op == StatementCode::Op::Param) parameters_.emplace_back(statement.name, step.slot);
            break;
        }
        case Statement::Kind::Assign:
            step.op = StatementCode::Op::Let;
            try {
                step.value = compile_expression(statement.value);
                step.slot = assigned_slot(statement);
            } catch (const CompileError&) {
                return;
            }
            break;
        case Statement::Kind::While:
            step.op = StatementCode::Op::While;
            step.value = compile_or_broken(statement.value);
            ++loops_;
            compile_scoped(statement.statements, step.steps);
            --loops_;
            break;
        case Statement::Kind::For: return compile_loop(statement, out);
        case Statement::Kind::If: {
            step.op = StatementCode::Op::If;
            step.value = compile_or_broken(statement.value);
            compile_scoped(statement.statements, step.steps);
            compile_scoped(statement.otherwise, step.otherwise);
            break;
        }
        case Statement::Kind::Function: return compile_function(statement, out);
        case Statement::Kind::Return:
            step.op = StatementCode::Op::Return;
            step.has_value = statement.has_value;
            if (step.has_value) step.value = compile_or_broken(statement.value);
            break;
        case Statement::Kind::Call:
            if (!compile_call_statement(statement, step)) return;
            break;
        case Statement::Kind::Group: {
            step.op = StatementCode::Op::Group;
            step.word = statement.word;
            bool failed = false;
            step.body = compile_body(statement.body, statement.word, &group_spec(), failed);
            step.broken = failed;
            step.unclosed = statement.broken;
            compile_scoped(statement.statements, step.steps);
            break;
        }
        case Statement::Kind::Include: return compile_include(statement, out);
    }
    out.push_back(std::move(step));
}

void Compiler::compile_loop(const Statement& statement, std::vector<StatementCode>& out) {
    StatementCode loop;
    loop.op = statement.over_list ? StatementCode::Op::Each : StatementCode::Op::Range;
    loop.keyword = statement.keyword;
    loop.name = statement.name;
    loop.name_span = statement.name_span;
    loop.top_level = loops_ == 0;
    try {
        loop.value = compile_expression(statement.value);
        if (!statement.over_list) loop.end = compile_expression(statement.end);
    } catch (const CompileError&) {
        return;
    }
    open_scope();
    loop.slot = bind(statement.name, statement.name_span, "for");
    ++loops_;
    compile_statements(statement.statements, loop.steps);
    --loops_;
    close_scope();
    out.push_back(std::move(loop));
}

void Compiler::compile_function(const Statement& statement, std::vector<StatementCode>& out) {
    StatementCode step;
    step.op = StatementCode::Op::Function;
    step.keyword = statement.keyword;
    step.name = statement.name;
    step.name_span = statement.name_span;
    step.slot = bind(statement.name, statement.name_span, statement.shape_value ? "shape" : "fn");
    auto code = std::make_shared<FunctionCode>();
    code->name = statement.name;
    code->name_span = statement.name_span;
    code->parameters = uint32_t(statement.parameters.size());
    code->file_origin = statement.keyword.origin;
    functions_.emplace_back();
    functions_.back().code = code.get();
    functions_.back().scopes.emplace_back();
    for (const auto& [name, span] : statement.parameters) bind(name, span, "parameter");
    const int outer_loops = loops_;
    loops_ = 0;
    compile_statements(statement.statements, code->steps);
    loops_ = outer_loops;
    code->slots = functions_.back().most_slots;
    functions_.pop_back();
    step.function = std::move(code);
    out.push_back(std::move(step));
}

// The included file read (once: again from the text held), parsed and compiled in place, its
// names joining the scope of the include.
void Compiler::compile_include(const Statement& statement, std::vector<StatementCode>& out) {
    const Span path_span = statement.name_span;
    const LibraryFile* library = nullptr;
    fs::path path;
    if (names_standard_library(statement.word)) {
        library = find_library_file(fs::path(statement.word).lexically_normal().string());
        if (!library) return missing_library_file(statement);
        path = std::string(library_display_prefix()) + std::string(statement.word.substr(4));
    } else {
        path = include_search(statement);
    }
    std::error_code ignored;
    const std::string canonical = library ? path.string() : fs::weakly_canonical(path, ignored).string();
    if (std::find(include_stack_.begin(), include_stack_.end(), canonical) != include_stack_.end()) {
        diagnostics_.error(sources_, path_span, "'" + statement.word + "' includes itself (through the files noted)");
        return;
    }
    if (int(include_stack_.size()) > kMaxIncludeDepth) {  // the scene and 32 includes below it
        diagnostics_.error(sources_, path_span, "includes are nested too deeply (more than 32 files)");
        return;
    }
    uint32_t file_origin = 0;
    if (auto known = included_.find(canonical); known != included_.end()) {
        file_origin = sources_.add_include_again(known->second, path_span);
    } else {
        InputFile input =
            library ? InputFile{std::string(library->text), {}} : read_input_file(path.string(), kMaxSceneFileBytes);
        if (!input.problem.empty()) {
            std::string searched;
            for (const std::string& folder : include_dirs_) searched += (searched.empty() ? "" : ", ") + folder;
            diagnostics_.error(sources_, path_span,
                               "cannot include '" + path.lexically_normal().string() + "': " + input.problem +
                                   (searched.empty() || fs::path(statement.word).is_absolute()
                                        ? ""
                                        : " (nor is it in the include folders " + searched + ")"));
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
                           "the scene includes more than 256 MiB of text in all (each include counted; the limit)");
        return;
    }
    StatementCode step;
    step.op = StatementCode::Op::Include;
    step.keyword = statement.keyword;
    step.name_span = path_span;
    step.word = statement.word;
    step.origin = file_origin;
    include_stack_.push_back(canonical);
    const Program program = parse_program(file, diagnostics_, file_origin);
    compile_statements(program.statements, step.steps);
    include_stack_.pop_back();
    out.push_back(std::move(step));
}

// Where `include "WORD"` finds its file: beside the including file, else in the first of the
// search folders (-I, then TRACER_PATH) that has it; beside it when none has (reported then).
fs::path Compiler::include_search(const Statement& statement) const {
    const fs::path written = statement.word;
    const fs::path beside = fs::path(sources_.file(statement.name_span).path()).parent_path() / written;
    if (written.is_absolute()) return written;
    std::error_code ignored;
    if (fs::exists(beside, ignored)) return beside;
    for (const std::string& folder : include_dirs_)
        if (fs::path candidate = fs::path(folder) / written; fs::exists(candidate, ignored)) return candidate;
    return beside;
}

// `include "std/NAME"` of a file the standard library does not have: its files listed.
void Compiler::missing_library_file(const Statement& statement) {
    std::string names;
    for (const LibraryFile& file : standard_library()) names += (names.empty() ? "" : ", ") + std::string(file.name);
    diagnostics_.error(sources_, statement.name_span,
                       "the standard library has no file " + in_quotes(statement.word) + "; it has " + names);
}

// A body's entries compiled, their keys looked up in `spec` (the block's table; none for an
// unknown block); `failed` is set if an entry had a mistake (reported; the entry is kept, broken).
std::shared_ptr<CompiledBody> Compiler::compile_body(const BodyCode& code, const std::string& kind,
                                                     const BlockSpec* spec, bool& failed) {
    auto body = std::make_shared<CompiledBody>();
    body->kind = kind;
    body->spec = spec;
    body->open_brace = code.open_brace;
    body->close_brace = code.close_brace;
    for (const EntryCode& entry : code.entries) {
        CompiledEntry out;
        out.key = entry.key;
        out.key_span = entry.key_span;
        out.spec = spec ? spec->find_key(entry.key) : nullptr;
        const KeySpec* key = out.spec;
        if (entry.value.kind == Expr::Kind::Block && entry.value.text.empty()) {
            // A nested block: its own table (rotate, transform), or a material's.
            const BlockSpec* nested = key && key->block                            ? key->block
                                      : key && key->type == ValueType::MaterialRef ? find_block_spec("material")
                                                                                   : nullptr;
            out.nested = true;
            out.body = compile_body(*entry.value.body, entry.key, nested, failed);
        } else {
            try {
                // A path is any expression of a string (`dir + "/x.obj"`, a name, a call); a word,
                // a dotted one or a division (`file bunny.obj`, `file meshes/a.obj`) was meant as
                // a path in quotes.
                ExprCode named;
                const Expr::Kind value_kind = entry.value.kind;
                const bool may_be_string = value_kind == Expr::Kind::String ||
                                           (value_kind == Expr::Kind::Binary && entry.value.op == '+') ||
                                           value_kind == Expr::Kind::Call || value_kind == Expr::Kind::Conditional ||
                                           value_kind == Expr::Kind::Index;
                if (key && key->type == ValueType::Path && !may_be_string &&
                    !(value_kind == Expr::Kind::Name &&
                      resolve(entry.value.text, functions_.size() - 1, entry.value.span, named)))
                    fail(entry.value.span,
                         path_expected(entry.key, sources_.file(entry.value.span).slice(entry.value.span)));
                const bool word_key = key && (key->type == ValueType::MaterialRef || key->type == ValueType::Choice);
                out.value = is_choice_word(key, entry.value)
                                ? word(entry.value)  // `encoding srgb` beside a function named srgb
                                : compile_expression(entry.value, may_be_word(key, entry.value), word_key);
            } catch (const CompileError&) {
                // Kept, broken: the block's other entries are still checked, and the key is
                // not reported missing.
                failed = true;
                out.value = constant(RuntimeValue::broken(), entry.value.span);
            }
        }
        body->entries.push_back(std::move(out));
    }
    return body;
}

}  // namespace tracer
