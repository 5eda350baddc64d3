#include "lang/reference_doc.h"

#include <charconv>
#include <cmath>
#include <sstream>
#include <string_view>
#include <utility>

#include "lang/internal/builtins.h"
#include "lang/schema.h"
#include "lang/standard_library.h"

namespace tracer {
namespace {

// The allowed values of a key, e.g. "> 0", ">= 0", "0 < x < 180", "1 to 16384".
std::string allowed_text(const KeySpec& key) {
    std::string text;
    bool has_min = !std::isinf(key.min), has_max = !std::isinf(key.max);
    if (has_min && has_max) {
        if (key.min_open || key.max_open)
            text = format_number(key.min) + (key.min_open ? " < x " : " <= x ") + (key.max_open ? "< " : "<= ") +
                   format_number(key.max);
        else
            text = format_number(key.min) + " to " + format_number(key.max);
    } else if (has_min) {
        text = (key.min_open ? "> " : ">= ") + format_number(key.min);
    }
    if (key.type == ValueType::Triple && has_min) text += " (each component)";
    if (key.nonzero) text += text.empty() ? "not zero length" : "; not zero length";
    if (key.perfect_square) text += "; a perfect square";
    if (key.power_of_two) text += "; a power of two";
    if (key.mirror_size) text += "not 0, at least 1e-30 in size (each component; negative mirrors)";
    for (size_t i = 0; i < key.choices.size(); ++i) text += (i == 0 ? "`" : ", `") + std::string(key.choices[i]) + "`";
    return text.empty() ? "any" : text;
}

// The statements of the language, one row each: its keyword (empty: a call), how it is
// written and what it does. The reference lists them; editors complete and explain them.
struct StatementSpec {
    std::string_view keyword;
    std::string_view syntax;
    std::string_view meaning;
};
const StatementSpec kStatements[] = {
    {"let", "let NAME = value",
     "names a value: a number, vector, boolean, string, list, `material { ... }`, `transform { ... }` or a "
     "pattern (`checker { ... }`)"},
    {"", "let NAME = sphere { ... }",
     "names a shape value: a block that puts something in the scene (a shape, a light, a `group` or a solid: "
     "`let die = difference { ... }`), made again wherever `NAME` stands alone on a line, placed by the groups "
     "around it there, from the names as they were where it was written"},
    {"", "NAME = value",
     "gives a name defined before (by `let`, in this function or outside all functions) a new value; `let` "
     "inside braces would make a new name there instead"},
    {"param", "param NAME = value", "a `let` that `-D NAME=VALUE` on the command line may change (top level only)"},
    {"for", "for NAME in A..B { ... }", "runs its statements for NAME = A, A + 1, ..., B - 1"},
    {"for", "for NAME in LIST { ... }", "runs its statements for each value of the list, in order"},
    {"while", "while CONDITION { ... }",
     "runs its statements again and again while the condition is true (each pass counts as a loop iteration)"},
    {"if", "if CONDITION { ... } else { ... }",
     "runs the first statements if the condition is true, else the others (`else` and its braces may be left "
     "out; `else if` chains)"},
    {"fn", "fn NAME(A, B) { ... }", "defines a function; `return VALUE` ends it with a value"},
    {"", "NAME(a, b)", "calls a function for the blocks it makes"},
    {"print", "print(a, b, ...)",
     "writes the values as `str` does, separated by spaces, with this file, line and column, to standard error "
     "(and into `--diagnostics json` and the language server), in the order the scene runs; the first 1,000 "
     "lines, the rest counted"},
    {"group", "group { translate ... rotate ... scale ... transform ... statements }",
     "places every block made inside by its placement steps, in the order written (written first; nested groups "
     "compose)"},
    {"union", "union { placement ... statements }",
     "a group whose shapes show all their faces (POV-Ray's union); inside another solid, a solid like `merge`"},
    {"merge", "merge { placement ... statements }",
     "one solid (CSG) of every closed shape (sphere, box, cylinder, cone, closed mesh, plane: the half-space "
     "behind it) and solid made inside: where they overlap, their inner faces vanish (for glass); placed like a "
     "group"},
    {"intersection", "intersection { placement ... statements }",
     "the solid inside every part made inside (a lens: two spheres); each face keeps its shape's material"},
    {"difference", "difference { placement ... statements }",
     "the first part made inside minus all the others (a die: a box minus spheres); a cut face is the cutter's "
     "surface, with its material"},
    {"include", "include \"file.scn\"",
     "runs another file in place: found beside this file, else in the -I folders and then TRACER_PATH's, in "
     "order; `include \"std/NAME.scn\"` is the standard library built into tracer (below)"},
};

// The words of expressions: operators and literals.
const std::pair<std::string_view, std::string_view> kExpressionWords[] = {
    {"and", "true when both sides are true (the right side is not evaluated when the left is false)"},
    {"or", "true when either side is true (the right side is not evaluated when the left is true)"},
    {"not", "the opposite of a condition"},
    {"true", "the condition that holds"},
    {"false", "the condition that does not hold"},
    {"in", "`for NAME in A..B` or `for NAME in LIST`"},
    {"else", "the statements (or value) of an `if` when its condition is false"},
    {"return", "ends a function, with a value when one follows"},
};

std::string occurs_text(Occurs occurs) {
    switch (occurs) {
        case Occurs::ExactlyOnce: return "exactly one per scene";
        case Occurs::AtMostOnce: return "at most one";
        case Occurs::Any: return "any number";
    }
    return "";
}

}  // namespace

std::string standard_library_markdown();

std::string reference_markdown() {
    std::ostringstream out;
    out << "# Scene language reference\n\n"
           "<!-- Generated by `tracer --reference` from the block tables in src/lang/schema.cpp.\n"
           "     Do not edit by hand: a test fails when this file and the tables differ. -->\n\n"
           "The syntax is in [scene.ebnf](scene.ebnf); a tour is in [README.md](README.md).\n"
           "A scene is a sequence of blocks, `kind { key value ... }`. Every key is either\n"
           "required or has the default shown. Numbers are written `3`, `-0.5`, `.25`, `1e-3`;\n"
           "vectors `(x, y, z)`; a colour or a scale may be one number, meaning the same value\n"
           "in all three components. Paths are strings in double quotes, relative to the scene\n"
           "file's folder. `#` starts a comment that runs to the end of the line.\n";
    auto block_section = [&out](const BlockSpec* spec, std::string_view level) {
        out << "\n" << level << " `" << spec->kind << "`\n\n" << spec->summary << "\n\n";
        if (spec->top_level)
            out << "Written `" << spec->kind << (spec->named ? " NAME" : "") << " { ... }`; "
                << occurs_text(spec->occurs) << ".\n\n";
        out << "| key | type | default | allowed | meaning |\n|---|---|---|---|---|\n";
        for (const KeySpec& key : spec->keys) {
            out << "| `" << key.name << "` | " << describe(key.type) << " | "
                << (key.required() ? std::string("required") : "`" + std::string(key.default_value) + "`") << " | "
                << allowed_text(key) << " | " << key.meaning << " |\n";
        }
        if (!spec->example.empty()) out << "\nExample:\n\n```scn\n" << spec->example << "```\n";
    };
    for (const BlockSpec* spec : all_block_specs()) block_section(spec, "##");
    out << "\n## Patterns\n\n"
           "A material's `ka` and `kd` take a colour or a pattern, written `KIND { keys }` (`kd checker { }`)\n"
           "or named by `let` (`let floor = checker { ... }`, then `kd floor`). A pattern maps a point to a\n"
           "colour. The point is the hit in the shape's own coordinates (those its block is written in,\n"
           "before its placement and its groups'), so a pattern moves with its shape; the pattern's own\n"
           "steps (`scale`, `rotate`, `translate`, `transform`) place it on the shape, and its `mapping`\n"
           "turns the point into its coordinates. A checker's squares may be patterns themselves (up to 16\n"
           "levels), placed inside the checker's space; colour-map stops are colours. The guide's page\n"
           "docs/guide/patterns.md shows each with a picture; the noise is Perlin's improved noise (2002),\n"
           "defined exactly in src/scene/noise.h.\n";
    for (const BlockSpec* spec : pattern_specs()) block_section(spec, "###");
    out << "\n## Statements\n\n"
           "Between blocks (and inside braces) a scene may also have these; what they mean is in\n"
           "[README.md](README.md).\n\n"
           "| statement | what it does |\n|---|---|\n";
    for (const StatementSpec& statement : kStatements)
        out << "| `" << statement.syntax << "` | " << statement.meaning << " |\n";
    out << "\nValues may be expressions: `+ - * /`, unary minus, parentheses, vectors `(a, b, c)`, components\n"
           "`v.x`, `v.y`, `v.z`, lists `[a, b, c]` and their items `list[i]` (from 0), comparisons\n"
           "`== != < <= > >=`, `and`, `or`, `not`, `true`, `false`, `if CONDITION { A } else { B }`, calls\n"
           "of the scene's functions, these names:\n\n"
           "| name | value |\n|---|---|\n";
    for (const BuiltinConstant& constant : all_constants())
        out << "| `" << constant.name << "` | " << constant.meaning << " |\n";
    out << "\nand these functions (angles in degrees):\n\n"
           "| function | arguments | gives |\n|---|---|---|\n";
    for (const Builtin& function : all_builtins())
        out << "| `" << function.name << "` | " << function.arity << " | " << function.meaning << " |\n";
    out << standard_library_markdown();
    return out.str();
}

// Each file of the standard library: its opening comment, then every name it defines (a `let`
// or `fn` at the start of a line) with what it is, as written.
std::string standard_library_markdown() {
    std::ostringstream out;
    out << "\n## Standard library\n\n"
           "Files built into tracer, the same on every machine: `include \"std/NAME.scn\"` runs one (a file on\n"
           "disk is never looked at for a `std/` path). Their names join the scene's like any include's.\n";
    for (const LibraryFile& file : standard_library()) {
        out << "\n### `" << file.name << "`\n\n";
        std::istringstream lines{std::string(file.text)};
        std::string line;
        bool opening = true;
        std::ostringstream names;
        while (std::getline(lines, line)) {
            if (opening && line.starts_with("#")) {
                out << (line.size() > 2 ? line.substr(2) : "") << '\n';
                continue;
            }
            opening = false;
            if (line.starts_with("let ")) {
                const size_t equals = line.find(" = ");
                names << "| `" << line.substr(4, equals - 4) << "` | `" << line.substr(equals + 3) << "` |\n";
            } else if (line.starts_with("fn ")) {
                names << "| `" << line.substr(3, line.find(')') - 2) << "` | a function |\n";
            }
        }
        out << "\n| name | defined as |\n|---|---|\n" << names.str();
    }
    return out.str();
}

nlohmann::json language_json() {
    nlohmann::json blocks = nlohmann::json::array();
    std::vector<const BlockSpec*> specs = all_block_specs();
    specs.insert(specs.end(), pattern_specs().begin(), pattern_specs().end());
    for (const BlockSpec* spec : specs) {
        nlohmann::json keys = nlohmann::json::array();
        for (const KeySpec& key : spec->keys)
            keys.push_back({{"name", key.name},
                            {"type", describe(key.type)},
                            {"default", key.required() ? nlohmann::json(nullptr) : nlohmann::json(key.default_value)},
                            {"allowed", allowed_text(key)},
                            {"meaning", key.meaning},
                            {"block", key.block ? nlohmann::json(key.block->kind) : nlohmann::json(nullptr)},
                            {"choices", key.choices}});
        blocks.push_back({{"kind", spec->kind},
                          {"named", spec->named},
                          {"top_level", spec->top_level},
                          {"occurs", occurs_text(spec->occurs)},
                          {"summary", spec->summary},
                          {"example", spec->example},
                          {"pattern", find_pattern_spec(spec->kind) == spec},
                          {"keys", std::move(keys)}});
    }
    nlohmann::json statements = nlohmann::json::array();
    for (const StatementSpec& statement : kStatements)
        statements.push_back(
            {{"keyword", statement.keyword}, {"syntax", statement.syntax}, {"meaning", statement.meaning}});
    nlohmann::json words = nlohmann::json::array();
    for (const auto& [word, meaning] : kExpressionWords) words.push_back({{"word", word}, {"meaning", meaning}});
    nlohmann::json constants = nlohmann::json::array();
    for (const BuiltinConstant& constant : all_constants())
        constants.push_back({{"name", constant.name}, {"meaning", constant.meaning}});
    nlohmann::json functions = nlohmann::json::array();
    for (const Builtin& function : all_builtins())
        functions.push_back({{"name", function.name}, {"arity", function.arity}, {"meaning", function.meaning}});
    nlohmann::json library = nlohmann::json::object();  // name -> text: editors show its definitions
    for (const LibraryFile& file : standard_library()) library[std::string(file.name)] = file.text;
    return {{"blocks", std::move(blocks)},       {"statements", std::move(statements)},
            {"words", std::move(words)},         {"constants", std::move(constants)},
            {"functions", std::move(functions)}, {"library", std::move(library)}};
}

}  // namespace tracer
