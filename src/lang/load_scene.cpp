#include "lang/load_scene.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

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
    std::error_code error;
    std::string problem;
    if (std::filesystem::is_directory(path, error)) {
        problem = "it is a directory";
    } else {
        std::ifstream in(path, std::ios::binary);
        if (in) {
            std::ostringstream text;
            text << in.rdbuf();
            if (!in.bad()) return load_scene_text(path, text.str());
        }
        problem = std::strerror(errno);
    }
    LoadResult result;
    result.unreadable = true;
    result.diagnostics.report(Severity::Error, Diagnostics::whole_file(path),
                              "cannot read the scene file: " + problem);
    return result;
}

}  // namespace tracer
