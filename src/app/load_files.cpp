#include "app/load_files.h"

#include <algorithm>
#include <ostream>

#include "io/image_file.h"
#include "io/obj_mesh.h"
#include "lang/standard_library.h"

namespace tracer {

ReportLoad print_diagnostics_to(std::ostream& out) {
    return [&out](const LoadReport& report) { report.diagnostics.print(out); };
}

namespace {

// The image files of `scene` that `files` holds, given their texels; read ones added to it.
bool load_images_once(SceneDescription& scene, Diagnostics& diagnostics, FileCache* files) {
    if (files)
        for (ImageFile& image : scene.images)
            if (auto read = files->images.find(image.path); read != files->images.end()) image.texels = read->second;
    if (!load_images(scene, diagnostics)) return false;
    if (files)
        for (const ImageFile& image : scene.images) files->images.emplace(image.path, image.texels);
    return true;
}

// load_scene_with_meshes' steps after the scene's text has run (`loaded`).
std::optional<LoadedScene> finish_loading(LoadResult loaded, const SceneInput& input,
                                          const std::function<void(SceneDescription&)>& adjust,
                                          const ReportLoad& report, FileCache* files) {
    std::optional<SceneMeshes> meshes;
    const std::string name = input.path == "-" && !input.text ? input.standard_input_name : input.path;
    const bool from_file = input.path != "-" && !input.text;  // a file the load read
    if (loaded.scene) {
        if (adjust) adjust(*loaded.scene);
        const std::string problem = render_settings_problem(loaded.scene->render);
        if (!problem.empty())
            loaded.diagnostics.report(Severity::Error, Diagnostics::whole_file(name),
                                      "with the command line's overrides, " + problem);
        else if (load_images_once(*loaded.scene, loaded.diagnostics, files))
            meshes = load_meshes(*loaded.scene, loaded.diagnostics, files ? &files->meshes : nullptr);
    }
    LoadReport found{loaded.diagnostics, {}, loaded.unreadable, &loaded.names};
    if (from_file) found.files_read.push_back(input.path);
    for (const std::string& path : loaded.included_paths)
        if (!is_library_path(path)) found.files_read.push_back(path);  // not a file: part of tracer
    if (loaded.scene)
        for (const Mesh& mesh : loaded.scene->meshes) found.files_read.push_back(mesh.path);
    if (loaded.scene)
        for (const ImageFile& image : loaded.scene->images) found.files_read.push_back(image.path);
    std::sort(found.files_read.begin() + from_file, found.files_read.end());  // each once
    found.files_read.erase(std::unique(found.files_read.begin(), found.files_read.end()), found.files_read.end());
    if (report) report(found);
    if (!loaded.scene || !meshes) return std::nullopt;
    return LoadedScene{std::move(*loaded.scene), std::move(*meshes)};
}

}  // namespace

std::optional<LoadedScene> load_scene_with_meshes(const SceneInput& input,
                                                  const std::function<void(SceneDescription&)>& adjust,
                                                  const ReportLoad& report) {
    LoadResult loaded = input.text ? load_scene_text(input.path, *input.text, false, input.arguments)
                                   : load_scene(input.path, input.arguments, {}, input.standard_input_name);
    return finish_loading(std::move(loaded), input, adjust, report, nullptr);
}

std::optional<LoadedScene> load_frame_with_meshes(SceneProgram& program, const FrameTime& frame,
                                                  const SceneInput& input,
                                                  const std::function<void(SceneDescription&)>& adjust,
                                                  const ReportLoad& report, FileCache& files) {
    return finish_loading(program.run(frame), input, adjust, report, &files);
}

}  // namespace tracer
