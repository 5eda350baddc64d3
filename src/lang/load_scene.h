// The front end in one call: read a scene file, parse it, validate it.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/diagnostics.h"
#include "lang/interpreter.h"
#include "scene/scene.h"

namespace tracer {

// A name the scene defines, located (NameDefinition with its place resolved).
struct DefinedName {
    std::string name;
    std::string_view kind;
    std::string path;
    int line = 0, column = 0;
};

struct LoadResult {
    std::optional<SceneDescription> scene;  // empty when there were errors
    Diagnostics diagnostics;
    bool unreadable = false;                  // the scene file itself could not be read
    std::vector<std::string> included_paths;  // every file included, also when there were errors
    std::vector<DefinedName> names;           // every name defined (up to kMostNamesRecorded)
};

// Loads the scene at `path`; every problem found is in the result's diagnostics. A `path` of
// "-" reads standard input, named `standard_input_name` in messages, relative paths starting
// from that name's folder (by default kStandardInputName: the working folder).
inline constexpr std::string_view kStandardInputName = "<stdin>";
LoadResult load_scene(const std::string& path, const SceneArguments& arguments = {}, const InterpretLimits& limits = {},
                      std::string_view standard_input_name = kStandardInputName);

// Parses and validates scene text held in memory (`path` names it in messages and anchors
// relative paths). A `fragment` (an example of the reference) needs no camera.
LoadResult load_scene_text(const std::string& path, std::string text, bool fragment = false,
                           const SceneArguments& arguments = {}, const InterpretLimits& limits = {});

}  // namespace tracer
