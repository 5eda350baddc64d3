// One table per block kind: its keys, their types, defaults, ranges and meanings.
// The same tables drive validation, "did you mean" suggestions and grammar/reference.md,
// so the three cannot drift apart.
#pragma once

#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace tracer {

enum class ValueType {
    Number,       // a number
    Integer,      // a whole number
    Boolean,      // true or false
    Vector,       // (x, y, z)
    Triple,       // a number (meaning (v, v, v)) or (x, y, z): colours, per-axis scale
    Path,         // "a string", a file path relative to the scene file
    MaterialRef,  // the name of a material block, or an inline { ... } material
    Block,        // a nested { ... } block with its own table
    Choice,       // one of the names listed in KeySpec::choices
    Paint,        // a colour (as Triple) or a pattern block: checker { ... } (pattern_specs())
    ColorMap,     // a list of stops [value, colour]: [[0, (1, 0, 0)], [1, 1]]
};

struct BlockSpec;

struct KeySpec {
    std::string_view name;
    ValueType type;
    std::string_view default_value;                         // written in scene syntax; empty means required
    double min = -std::numeric_limits<double>::infinity();  // applies to every component
    double max = std::numeric_limits<double>::infinity();
    bool min_open = false;  // true: the minimum itself is not allowed
    bool max_open = false;
    bool nonzero = false;         // vectors: must not have zero length
    bool perfect_square = false;  // whole numbers: must be N * N (samples)
    bool power_of_two = false;    // numbers: must be 2^k (adaptive_cell)
    bool mirror_size = false;     // sizes that may be negative (mirroring): |x| >= kSmallestSize
    bool placement_step = false;  // scale, rotate, translate, transform of a placed block: each may
                                  // repeat, and they apply in the order written
    std::string_view meaning;
    const BlockSpec* block = nullptr;       // ValueType::Block: the nested block's table
    std::vector<std::string_view> choices;  // ValueType::Choice: the allowed names

    bool required() const { return default_value.empty(); }
};

enum class Occurs { ExactlyOnce, AtMostOnce, Any };

struct BlockSpec {
    std::string_view kind;
    bool named;      // `material shiny { ... }`: the block must have a name
    bool top_level;  // false for blocks that only appear nested (rotate)
    Occurs occurs;
    std::string_view summary;
    std::vector<KeySpec> keys;
    std::string_view example;  // a complete, valid fragment shown in the reference
    bool ordered = false;      // a list of steps: keys may repeat, and their order is kept (transform)

    const KeySpec* find_key(std::string_view key) const;
};

// Every block kind, top-level and nested, in the order the reference documents them.
const std::vector<const BlockSpec*>& all_block_specs();
// The top-level block kind called `kind`, or nullptr.
const BlockSpec* find_block_spec(std::string_view kind);
// The tables of the patterns (checker, stripes, ... image), which are values, not statements.
const std::vector<const BlockSpec*>& pattern_specs();
// The pattern called `kind`, or nullptr.
const BlockSpec* find_pattern_spec(std::string_view kind);
// Most patterns one pattern may hold inside it, level within level (checker in checker).
constexpr int kMostPatternNesting = 16;
// The table of a group's placement (`group { translate ... }`).
const BlockSpec& group_spec();
// A number as messages and the reference print it: 100000, 0.5, 1e-30.
std::string format_number(double value);

// A readable name for a value type ("a number or (x, y, z)").
std::string_view describe(ValueType type);

}  // namespace tracer
