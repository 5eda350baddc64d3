// A scene compiled once and run again for each frame of an animation. A still scene's code is
// dropped statement by statement as it runs (load_scene); an animation keeps it, so that each
// frame only runs it with that frame's clock (FrameTime) and checks the blocks it makes.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "lang/interpreter.h"
#include "lang/load_scene.h"

namespace tracer {

class SceneProgram {
public:
    // The scene at `path` ("-": standard input, named `standard_input_name`), read now and
    // compiled by the first run().
    SceneProgram(const std::string& path, const SceneArguments& arguments,
                 std::string_view standard_input_name = kStandardInputName);
    ~SceneProgram();
    SceneProgram(const SceneProgram&) = delete;
    SceneProgram& operator=(const SceneProgram&) = delete;

    // The scene at `frame`, as load_scene gives it: the first call compiles and runs the file
    // (its included files too), later ones run the same code again. After a first run with
    // errors every later one gives them again.
    LoadResult run(const FrameTime& frame);
    // How many times the scene's text was compiled (1 once run, however many frames).
    int compilations() const;

private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace tracer
