#include "lang/load_scene.h"

#include "base/input_file.h"
#include "lang/internal/parser.h"
#include "lang/interpreter.h"
#include "lang/validate.h"

namespace tracer {

LoadResult load_scene_text(const std::string& path, std::string text, bool fragment, const SceneArguments& arguments,
                           const InterpretLimits& limits) {
    LoadResult result;
    Sources sources(std::make_unique<SourceFile>(path, std::move(text)));
    // Each block is checked and built as the interpreter makes it.
    ValidateOptions options;
    options.fragment = fragment;
    SceneBuilder builder(sources, result.diagnostics, options);
    const BlockSink check_and_build = [&](Block&& block) { return builder.add(block); };
    const EvaluatedScene evaluated = interpret(sources, result.diagnostics, arguments, limits, check_and_build);
    result.scene = builder.finish(evaluated.parameters);
    for (size_t i = 1; i < sources.files(); ++i) result.included_paths.push_back(sources.file_at(i).path());
    for (const NameDefinition& defined : evaluated.names) {  // line and column only: no line text copied
        const SourceFile& file = sources.file(defined.span);
        const LineCol at = file.locate(defined.span.begin);
        result.names.push_back({defined.name, defined.kind, file.path(), at.line, at.column});
    }
    if (result.scene)  // the files an output must never replace (with the scene and its meshes)
        result.scene->included_paths = result.included_paths;
    return result;
}

LoadResult load_scene(const std::string& path, const SceneArguments& arguments, const InterpretLimits& limits,
                      std::string_view standard_input_name) {
    // "-": standard input, named <stdin> in messages by default; its relative paths start from
    // the folder of its name (the working folder for <stdin>).
    const bool standard_input = path == "-";
    const std::string name = standard_input ? std::string(standard_input_name) : path;
    InputFile input =
        standard_input ? read_standard_input(kMaxSceneFileBytes) : read_input_file(path, kMaxSceneFileBytes);
    if (input.problem.empty()) return load_scene_text(name, std::move(input.text), false, arguments, limits);
    LoadResult result;
    result.unreadable = true;
    result.diagnostics.report(Severity::Error, Diagnostics::whole_file(name),
                              "cannot read the scene file: " + input.problem);
    return result;
}

}  // namespace tracer
