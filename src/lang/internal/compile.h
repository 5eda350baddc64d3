// Compiles the syntax tree (syntax_tree.h) into code for the interpreter (code.h): names
// resolved to slots in lexical scopes, functions' outer names captured, included files read,
// parsed and compiled in place. Mistakes found here (an undefined name, a name defined twice,
// an unknown function, an include that cannot be read) are reported once, where written.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "base/diagnostics.h"
#include "base/source.h"
#include "lang/internal/code.h"
#include "lang/internal/evaluated_scene.h"
#include "lang/internal/syntax_tree.h"

namespace tracer {

// Deepest chain of included files, and the most text the includes of one scene may compile.
constexpr int kMaxIncludeDepth = 32;
constexpr size_t kMaxIncludedBytes = size_t(256) << 20;

// Thrown after a mistake in an expression has been reported: the entry or statement is dropped.
struct CompileError {};

// The messages the compiler and the interpreter both give: a file-path key given something
// else (`written`: its source text), and a call with the wrong number of arguments.
std::string path_expected(std::string_view key, std::string_view written);
std::string arguments_expected(std::string_view function, size_t expected, size_t found);

class Compiler {
public:
    Compiler(Sources& sources, Diagnostics& diagnostics);

    // One top-level statement of the scene file, its steps appended to `out`.
    void compile_top_level(const Statement& statement, std::vector<StatementCode>& out);
    // A value alone, with no names in scope (a -D value, a default): false if it has an error
    // (reported). `top`: an unbound name is a word.
    bool compile_lone_value(const Expr& expr, bool top, ExprCode& out);
    // A block written alone (a default in the block tables), with no table: false if it has an
    // error (reported).
    std::shared_ptr<const CompiledBody> compile_lone_block(const BodyCode& code, bool& failed) {
        return compile_body(code, "default", nullptr, failed);
    }
    // Slots the top-level frame needs so far.
    uint32_t top_level_slots() const { return functions_.front().most_slots; }
    // The include stack starts with the scene file's canonical path (a scene including itself).
    void set_scene_path(std::string canonical) { include_stack_ = {std::move(canonical)}; }
    // The folders an include not found beside its file is looked for in, in order.
    void set_include_dirs(std::vector<std::string> folders) { include_dirs_ = std::move(folders); }
    // The names defined so far, in the order compiled (at most kMostNamesRecorded).
    std::vector<NameDefinition> take_definitions() { return std::move(definitions_); }
    // The parameters declared so far, by name (their global slots).
    const std::vector<std::pair<std::string, uint32_t>>& parameters() const { return parameters_; }

private:
    struct NameInfo {
        uint32_t slot = 0;
        Span defined_at;
        bool from_let = false;     // defined by a `let` (not a loop, a parameter or a function)
        bool read = false;         // some expression reads it
        bool assigned = false;     // some assignment changes it
        bool shape_value = false;  // defined by `let NAME = sphere { ... }` (a block that makes things)
        bool function = false;     // defined by `fn`
    };
    using Scope = std::unordered_map<std::string, NameInfo>;
    // The code being compiled at one level: the top level, or a function's body.
    struct FunctionLevel {
        FunctionCode* code = nullptr;  // none for the top level
        std::vector<Scope> scopes;
        uint32_t next_slot = 0, most_slots = 0;
        std::map<std::string, uint32_t, std::less<>> capture_index;
    };

    // Statements.
    void compile_statements(const std::vector<Statement>& statements, std::vector<StatementCode>& out);
    void compile_statement(const Statement& statement, std::vector<StatementCode>& out);
    void compile_loop(const Statement& statement, std::vector<StatementCode>& out);
    void compile_function(const Statement& statement, std::vector<StatementCode>& out);
    void compile_include(const Statement& statement, std::vector<StatementCode>& out);
    std::filesystem::path include_search(const Statement& statement) const;
    void missing_library_file(const Statement& statement);
    // `statements` in a scope of their own (a loop's, a branch's, a group's body).
    void compile_scoped(const std::vector<Statement>& statements, std::vector<StatementCode>& out);
    std::shared_ptr<CompiledBody> compile_body(const BodyCode& code, const std::string& kind, const BlockSpec* spec,
                                               bool& failed);

    // Expressions.
    ExprCode compile_expression(const Expr& expr, bool top = false, bool word_key = false);
    ExprCode compile_arithmetic(const Expr& expr);
    ExprCode compile_or_broken(const Expr& expr);
    bool is_print(const Expr& call);
    bool compile_call_statement(const Statement& statement, StatementCode& step);
    void check_placed_value(const Expr& name);
    ExprCode compile_name(const Expr& expr, bool top, bool word_key);
    ExprCode compile_call(const Expr& expr);
    [[noreturn]] void fail(Span span, std::string message);

    // Names.
    bool resolve(const std::string& name, size_t level, Span span, ExprCode& out);
    uint32_t bind(const std::string& name, Span defined_at, std::string_view kind);
    uint32_t assigned_slot(const Statement& statement);
    void record(const std::string& name, Span defined_at, std::string_view kind);
    void open_scope();
    void close_scope();
    std::vector<std::string_view> names_in_scope() const;

    Sources& sources_;
    Diagnostics& diagnostics_;
    std::vector<FunctionLevel> functions_;
    std::vector<std::string> include_stack_;
    std::vector<std::string> include_dirs_;
    std::map<std::string, uint32_t> included_;  // each file read, by canonical path: its first origin
    size_t included_bytes_ = 0;
    std::vector<std::pair<std::string, uint32_t>> parameters_;
    std::vector<NameDefinition> definitions_;
    int loops_ = 0;  // loops around the statement compiled (at the top level of the file or function)
};

}  // namespace tracer
