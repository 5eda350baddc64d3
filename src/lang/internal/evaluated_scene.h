// The scene as evaluated: blocks of `key value` entries holding plain values (numbers, vectors,
// strings, words, nested blocks), before any meaning is given to them. The interpreter builds
// it from the program as written (syntax_tree.h); validation checks it against the block tables
// (schema.h) and produces the scene description.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/source.h"

namespace tracer {

struct Body;

// A name the scene defines, for editors: `let`, `param`, `for`, `fn`, a function's parameter
// or a named material block, where it is written.
struct NameDefinition {
    std::string name;
    std::string_view kind;  // "let", "param", "for", "fn", "shape", "parameter", "material"
    Span span;
};
// Editors need no more of them than this (a generated scene may define millions).
constexpr size_t kMostNamesRecorded = 100000;

struct PlainValue {
    // Broken: its error was reported where it was made; the key counts as given, and nothing
    // more is said of it (no second message), but its block is not built.
    enum class Kind { Number, Vector, String, Identifier, Block, List, Broken };
    Kind kind = Kind::Number;
    Span span;
    double number = 0;               // Number
    std::vector<double> components;  // Vector
    std::vector<Span> component_spans;
    std::string text;               // String (contents), Identifier, or a Block's kind when written as a value
    std::shared_ptr<Body> body;     // Block (an inline block such as `material { ... }`)
    std::vector<PlainValue> items;  // List (a colour map's stops)
};

inline bool is_number(const PlainValue& value) {
    return value.kind == PlainValue::Kind::Number;
}
inline bool is_vector(const PlainValue& value) {
    return value.kind == PlainValue::Kind::Vector;
}
// What a value is, for messages: "a number", "a vector of 3 numbers", "the word 'sah'".
std::string plain_kind(const PlainValue& value);

struct KeySpec;
struct BlockSpec;

struct Entry {
    std::string key;
    Span key_span;
    PlainValue value;
    const KeySpec* spec = nullptr;  // the key's row in its block's table, when already looked up
};

struct Body {
    Span open_brace;
    Span close_brace;
    std::vector<Entry> entries;
};

// The placement of a group around a block: its `group { ... }` keys (scale, rotate, translate or
// a transform), and the group around it, if any. Shared by every block made inside. A solid's
// block (union, merge, intersection, difference) is a group too: what is made inside are its parts.
struct Group {
    std::string kind;  // group, union, merge, intersection or difference
    Span keyword;
    Body placement;
    bool broken = false;  // its placement had an error (reported)
    std::shared_ptr<const Group> outer;
};

struct Block {
    std::string kind;
    const BlockSpec* spec = nullptr;  // the kind's table, when already looked up
    Span kind_span;
    std::string name;  // empty when the block has no name
    Span name_span;
    Body body;
    bool broken = false;                 // a syntax error was reported inside; do not validate further
    std::shared_ptr<const Group> group;  // the innermost group it was made in, if any
};

struct EvaluatedScene {
    std::vector<Block> blocks;
    std::vector<std::pair<std::string, PlainValue>> parameters;  // each `param` and the value it took
    std::vector<NameDefinition> names;                           // the names defined, for editors
};

}  // namespace tracer
