// Runs a scene program into the blocks of plain values that validation checks
// (evaluated_scene.h): each top-level statement parsed (syntax_tree.h), compiled (code.h) and
// run in turn, expressions computed, loops unrolled, functions called, included files compiled
// in place. Every value in a block keeps the span of the expression that made it, tagged with
// the loop iteration, call or include it came from (Sources), so that later messages can point
// at it and say which iteration it was.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/diagnostics.h"
#include "base/source.h"
#include "lang/internal/evaluated_scene.h"

namespace tracer {

// Most blocks one scene may generate, most loop iterations and operations it may run (its work:
// each statement run and each operation of an expression evaluated counts one), most list
// items it may make, and the deepest its calls may nest (each an error at its place).
constexpr size_t kMaxGeneratedBlocks = 2'000'000;
constexpr size_t kMaxLoopIterations = 10'000'000;
constexpr size_t kMaxOperations = 500'000'000;
constexpr size_t kMaxListItems = 1'000'000;
constexpr size_t kMaxCallDepth = 10'000;

// The animation's time at the frame being made: what the built-in names `clock`, `clock_delta`
// and `frame_number` read (all 0 for a still image).
struct FrameTime {
    double clock = 0;        // from the animation's first clock value to its last (0 to 1 by default)
    double clock_delta = 0;  // the clock's step from one frame to the next
    int frame_number = 0;    // 0 for the first frame
};
enum class FrameValue : uint8_t { None, Clock, ClockDelta, FrameNumber };

// The value of `which` at `frame`.
inline double frame_value(const FrameTime& frame, FrameValue which) {
    return which == FrameValue::Clock        ? frame.clock
           : which == FrameValue::ClockDelta ? frame.clock_delta
                                             : double(frame.frame_number);
}

// -D NAME=VALUE from the command line, in order: each must name a `param` of the scene.
using ParameterValues = std::vector<std::pair<std::string, std::string>>;

// What a run gives the scene besides its file: the -D values, and the folders an include not
// found beside its file is looked for in, in order (-I, then TRACER_PATH's).
struct SceneArguments {
    ParameterValues parameters;
    std::vector<std::string> include_dirs;
    FrameTime frame;  // the animation's clock at this frame
    SceneArguments(ParameterValues given = {}, std::vector<std::string> folders = {})  // NOLINT: implicit
        : parameters(std::move(given)), include_dirs(std::move(folders)) {}
};

// How much one scene may make: each limit reached is an error at its place.
struct InterpretLimits {
    size_t max_blocks = kMaxGeneratedBlocks;  // lower for fuzzing, where memory and time are short
    size_t max_iterations = kMaxLoopIterations;
    size_t max_operations = kMaxOperations;
    size_t max_list_items = kMaxListItems;
    size_t max_call_depth = kMaxCallDepth;
};

// Takes each block as soon as it is made, instead of the EvaluatedScene keeping it: a scene of
// a million blocks is then never held whole. Returns true if it kept any of the block's spans
// (for a later message); false lets the interpreter forget the origins made for it alone.
using BlockSink = std::function<bool(Block&&)>;

// The scene file `sources.scene()` parsed and run, one statement at a time, with the command
// line's `arguments`; problems go to `diagnostics`. Included files are added to `sources`.
// Blocks go to `on_block` when it is set, else into the result.
EvaluatedScene interpret(Sources& sources, Diagnostics& diagnostics, const SceneArguments& arguments = {},
                         const InterpretLimits& limits = {}, const BlockSink& on_block = {});

// One value alone, with no names defined (a default in the block tables, a setting or a -D
// value from the command line). False, with the problem in `diagnostics`, if it has none.
bool evaluate_single_value(const SourceFile& file, Diagnostics& diagnostics, PlainValue& out);

}  // namespace tracer
