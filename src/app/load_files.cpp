#include "app/load_files.h"

#include <ostream>

#include "io/obj_mesh.h"
#include "lang/load_scene.h"

namespace tracer {

std::optional<LoadedScene> load_scene_with_meshes(const std::string& path,
                                                  const std::function<void(SceneDescription&)>& adjust,
                                                  std::ostream& errors, bool* unreadable,
                                                  const ParameterValues& parameters) {
    LoadResult loaded = load_scene(path, parameters);
    std::optional<SceneMeshes> meshes;
    if (loaded.scene) {
        if (adjust) adjust(*loaded.scene);
        const std::string problem = render_settings_problem(loaded.scene->render);
        if (problem.empty())
            meshes = load_meshes(*loaded.scene, loaded.diagnostics);
        else
            loaded.diagnostics.report(Severity::Error, Diagnostics::whole_file(path),
                                      "with the command line's overrides, " + problem);
    }
    loaded.diagnostics.print(errors);
    if (unreadable) *unreadable = loaded.unreadable;
    if (!loaded.scene || !meshes) return std::nullopt;
    return LoadedScene{std::move(*loaded.scene), std::move(*meshes)};
}

}  // namespace tracer
