// Gives meaning to a parsed scene: checks every block against its table (schema.h), fills
// in defaults, resolves materials and paths, and reports every problem it finds.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "base/diagnostics.h"
#include "base/source.h"
#include "lang/internal/evaluated_scene.h"
#include "scene/scene.h"

namespace tracer {

struct ValidateOptions {
    // A fragment (such as an example in the reference) need not have a camera, and its
    // unused materials are not worth a warning.
    bool fragment = false;
};

// The scene description, made a block at a time: blocks are checked and built as they come
// (the interpreter's on_block), and finish() gives it, or nothing if any error was reported
// (the errors are in `diagnostics`). Relative paths resolve against the folder of the file
// they are written in.
class SceneBuilder {
public:
    SceneBuilder(const Sources& sources, Diagnostics& diagnostics, const ValidateOptions& options = {});
    ~SceneBuilder();
    // Checks one block and adds what it describes. True if anything of it was kept for later
    // (a span that a later message may point at); false lets the interpreter forget the
    // contexts (Sources origins) it made only for this block.
    bool add(const Block& block);
    // The scene description (with the parameters the scene used), or nothing after errors.
    std::optional<SceneDescription> finish(const std::vector<std::pair<std::string, PlainValue>>& parameters);

private:
    struct State;
    std::unique_ptr<State> state_;
};

// Why `text`, as the value of `key` in the top-level block `block`, would be refused in a scene
// (the same message, e.g. "'width' must be between 1 and 16384, found 0"), or empty: the one
// check for settings given on the command line. A number accepted is written back into `text`
// as the value checked, exactly (`4*4` becomes `16`, `1e-400` becomes `0`), so that what is
// used is what was checked.
std::string setting_problem(std::string_view block, std::string_view key, std::string& text);

}  // namespace tracer
