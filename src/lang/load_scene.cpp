#include "lang/load_scene.h"

#include "base/input_file.h"
#include "lang/parser.h"
#include "lang/validate.h"

namespace tracer {

LoadResult load_scene_text(const std::string& path, std::string text, bool fragment) {
    LoadResult result;
    SourceFile file(path, std::move(text));
    SceneAst ast = parse_scene(file, result.diagnostics);
    ValidateOptions options;
    options.fragment = fragment;
    result.scene = validate_scene(ast, file, result.diagnostics, options);
    return result;
}

LoadResult load_scene(const std::string& path) {
    // "-": standard input, named <stdin> in messages; its mesh paths are relative to the
    // working folder (the folder of a file named <stdin> there).
    const bool standard_input = path == "-";
    const std::string name = standard_input ? std::string(kStandardInputName) : path;
    InputFile input =
        standard_input ? read_standard_input(kMaxSceneFileBytes) : read_input_file(path, kMaxSceneFileBytes);
    if (input.problem.empty()) return load_scene_text(name, std::move(input.text));
    LoadResult result;
    result.unreadable = true;
    result.diagnostics.report(Severity::Error, Diagnostics::whole_file(name),
                              "cannot read the scene file: " + input.problem);
    return result;
}

}  // namespace tracer
