// Everything a render needs from disk in one call: the scene file (read, parsed, validated),
// adjusted by the caller (command-line overrides), and the OBJ files of its meshes.
#pragma once

#include <functional>
#include <iosfwd>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/diagnostics.h"
#include "io/obj_mesh.h"
#include "lang/interpreter.h"
#include "lang/load_scene.h"
#include "lang/scene_program.h"
#include "scene/scene.h"
#include "scene/triangle_mesh.h"

namespace tracer {

struct LoadedScene {
    SceneDescription scene;
    SceneMeshes meshes;
};

// Where a scene comes from: a file, or standard input ("-") under a name of the caller's choice.
struct SceneInput {
    std::string path;
    // For "-": the name messages give it; relative paths start from its folder.
    std::string standard_input_name = std::string(kStandardInputName);
    SceneArguments arguments;  // -D values and include folders
    // The scene's text, when it is held in memory (the Python module's loads): `path` then only
    // names it in messages and anchors relative paths, and is not read.
    std::optional<std::string> text;
};

// What a load found besides the scene: every diagnostic, and every file it read (the scene, the
// files it includes, its meshes), also when it failed.
struct LoadReport {
    const Diagnostics& diagnostics;
    std::vector<std::string> files_read;
    bool unreadable = false;                          // the scene file itself could not be read
    const std::vector<DefinedName>* names = nullptr;  // every name the scene defines
};
using ReportLoad = std::function<void(const LoadReport&)>;

// A ReportLoad that prints the diagnostics as text on `out`.
ReportLoad print_diagnostics_to(std::ostream& out);

// Loads the scene of `input`, lets `adjust` change it before its meshes are read, and hands
// every diagnostic to `report`. nullopt on errors.
std::optional<LoadedScene> load_scene_with_meshes(const SceneInput& input,
                                                  const std::function<void(SceneDescription&)>& adjust,
                                                  const ReportLoad& report);

// The files an animation reads once for all its frames: meshes and image patterns' texels, by path.
struct FileCache {
    MeshFileCache meshes;
    std::map<std::string, std::shared_ptr<const Texels>> images;
};

// The same for one frame of an animation: the scene `program` run at `frame`, its mesh and image
// files read only if no earlier frame read them (`files`).
std::optional<LoadedScene> load_frame_with_meshes(SceneProgram& program, const FrameTime& frame,
                                                  const SceneInput& input,
                                                  const std::function<void(SceneDescription&)>& adjust,
                                                  const ReportLoad& report, FileCache& files);

}  // namespace tracer
