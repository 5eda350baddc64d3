#include "lang/scene_program.h"

#include <optional>

#include "base/big_stack.h"
#include "base/input_file.h"
#include "lang/internal/interpreter_class.h"
#include "lang/validate.h"

namespace tracer {

struct SceneProgram::State {
    std::string name;  // the scene's path in messages
    SceneArguments arguments;
    InputFile input;
    std::unique_ptr<Sources> sources;
    Diagnostics diagnostics;  // the interpreter's and compiler's, handed to each run's result
    std::unique_ptr<Interpreter> interpreter;
    bool failed = false;  // the first run had errors (reported then)
    bool unreadable = false;
    std::vector<DefinedName> names;
    int compilations = 0;
};

SceneProgram::SceneProgram(const std::string& path, const SceneArguments& arguments,
                           std::string_view standard_input_name)
    : state_(std::make_unique<State>()) {
    const bool standard_input = path == "-";
    state_->name = standard_input ? std::string(standard_input_name) : path;
    state_->arguments = arguments;
    state_->input =
        standard_input ? read_standard_input(kMaxSceneFileBytes) : read_input_file(path, kMaxSceneFileBytes);
}

SceneProgram::~SceneProgram() = default;

int SceneProgram::compilations() const {
    return state_->compilations;
}

LoadResult SceneProgram::run(const FrameTime& frame) {
    State& state = *state_;
    LoadResult result;
    if (state.failed) {
        result.unreadable = state.unreadable;
        result.diagnostics.report(Severity::Error, Diagnostics::whole_file(state.name),
                                  "the scene has errors (reported at its first run)");
        return result;
    }
    if (!state.input.problem.empty()) {  // as load_scene reports it
        result.unreadable = state.unreadable = state.failed = true;
        result.diagnostics.report(Severity::Error, Diagnostics::whole_file(state.name),
                                  "cannot read the scene file: " + state.input.problem);
        return result;
    }
    // Step 1: the blocks of this frame, checked and built as they come.
    const bool first = !state.interpreter;
    if (first) {
        state.sources =
            std::make_unique<Sources>(std::make_unique<SourceFile>(state.name, std::move(state.input.text)));
        ++state.compilations;
    }
    SceneBuilder builder(*state.sources, state.diagnostics);
    const BlockSink check_and_build = [&](Block&& block) { return builder.add(block); };
    EvaluatedScene evaluated;
    run_on_big_stack([&] {
        if (first) {
            SceneArguments arguments = state.arguments;
            arguments.frame = frame;
            state.interpreter =
                std::make_unique<Interpreter>(*state.sources, state.diagnostics, InterpretLimits{}, check_and_build);
            state.interpreter->keep_code(true);
            evaluated = state.interpreter->run(arguments);
        } else {
            evaluated = state.interpreter->run_again(frame, check_and_build);
        }
    });
    result.scene = builder.finish(evaluated.parameters);
    // Step 2: what load_scene_text gives besides the scene (the names: from the first run).
    for (size_t i = 1; i < state.sources->files(); ++i)
        result.included_paths.push_back(state.sources->file_at(i).path());
    if (first)
        for (const NameDefinition& defined : evaluated.names) {
            const SourceFile& file = state.sources->file(defined.span);
            const LineCol at = file.locate(defined.span.begin);
            state.names.push_back({defined.name, defined.kind, file.path(), at.line, at.column});
        }
    result.names = state.names;
    if (result.scene) result.scene->included_paths = result.included_paths;
    result.diagnostics = std::move(state.diagnostics);
    state.diagnostics = Diagnostics();
    state.failed = first && !result.scene;
    return result;
}

}  // namespace tracer
