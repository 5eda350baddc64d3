// The browser's tracer (tools/playground): a scene's text loaded as the command line loads a
// file, its world built once, and its image rendered a band of rows at a time into 8-bit RGBA,
// so that the page's worker can post progress and drop a render that a new edit made stale
// between two bands. Bound to JavaScript with embind.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <algorithm>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/diagnostics_json.h"
#include "app/load_files.h"
#include "io/eight_bit.h"
#include "io/web_pictures.h"
#include "lang/reference_doc.h"
#include "render/renderer.h"

namespace {

using nlohmann::json;

std::string text_of(const json& value) {
    return value.dump(-1, ' ', false, json::error_handler_t::replace);
}

// One scene of the page: loaded, its world, and the frame under way.
class Playground {
public:
    // Loads `text` as the scene file `path` (relative paths start from its folder); the load's
    // report as JSON text (app/diagnostics_json.h's load_report_json), "ok" false on errors.
    std::string load(const std::string& path, const std::string& text) {
        loaded_.reset();
        world_.reset();
        const tracer::SceneInput input{path, path, {}, text};
        std::string report;
        try {
            auto scene = tracer::load_scene_with_meshes(input, nullptr, [&](const tracer::LoadReport& found) {
                report = text_of(tracer::load_report_json(path, found));
            });
            if (scene) loaded_ = std::make_unique<tracer::LoadedScene>(std::move(*scene));
        } catch (const std::exception& error) {
            report = text_of(failure(path, error.what()));
        }
        return report;
    }

    // Starts a frame of the loaded scene at 1/`divisor` of its size (a preview: one sample a
    // pixel), building the world on the first frame; {"width", "height", "frame_width",
    // "frame_height" (the whole image's), "samples" (a pixel's)} or {"error"} as JSON.
    std::string start(int divisor) {
        if (!loaded_) return text_of({{"error", "no scene is loaded"}});
        try {
            frame_ = loaded_->scene;
            tracer::RenderSettings& render = frame_.render;
            divisor = std::max(divisor, 1);
            if (divisor > 1) {
                render.width = std::max(1, render.width / divisor);
                render.height = std::max(1, render.height / divisor);
                render.samples = 1;
                render.antialias = tracer::Antialias::Uniform;
            }
            if (!world_) world_ = std::make_unique<tracer::World>(loaded_->scene, loaded_->meshes, 1);
            rgba_.assign(size_t(render.width) * size_t(render.height) * 4, 255);
            return text_of({{"width", render.width},
                            {"height", render.height},
                            {"frame_width", loaded_->scene.render.width},
                            {"frame_height", loaded_->scene.render.height},
                            {"samples", render.samples}});
        } catch (const std::exception& error) {
            world_.reset();
            return text_of({{"error", error.what()}});
        }
    }

    // Renders rows [first, first + count) of the frame started into pixels(); the number of
    // rays they took, or -1 if the render failed (the frame is then dropped).
    double render_rows(int first, int count) {
        if (!world_ || rgba_.empty()) return -1;
        const tracer::RenderSettings& render = frame_.render;
        first = std::clamp(first, 0, render.height);
        count = std::clamp(count, 0, render.height - first);
        if (count == 0) return 0;
        try {
            tracer::RenderOptions options;
            options.threads = 1;
            options.crop = {0, first, render.width, count};
            tracer::Image band;
            tracer::RenderStats stats;
            tracer::render(*world_, frame_, options, band, stats);
            std::vector<unsigned char> rgb(band.rgb.size());
            tracer::eight_bit_rows(band, render.encoding == tracer::Encoding::Srgb, rgb.data());
            unsigned char* out = rgba_.data() + size_t(first) * size_t(render.width) * 4;
            for (size_t pixel = 0; pixel < rgb.size() / 3; ++pixel) std::copy_n(&rgb[pixel * 3], 3, out + pixel * 4);
            return double(stats.rays.total());
        } catch (const std::exception&) {
            rgba_.clear();
            return -1;
        }
    }

    // The frame's pixels, width x height RGBA bytes from the top row (a view into the module's
    // memory: copy it before the next call).
    emscripten::val pixels() const {
        return emscripten::val(emscripten::typed_memory_view(rgba_.size(), rgba_.data()));
    }

private:
    static json failure(const std::string& path, const std::string& why) {
        return {{"scene", path},
                {"ok", false},
                {"errors", 1},
                {"warnings", 0},
                {"diagnostics", json::array()},
                {"text", path + ": error: " + why + "\n"}};
    }

    std::unique_ptr<tracer::LoadedScene> loaded_;
    std::unique_ptr<tracer::World> world_;
    tracer::SceneDescription frame_;
    std::vector<unsigned char> rgba_;
};

// The language's tables (tracer --language-json) as JSON text: the editor's completion and hover.
std::string language() {
    return text_of(tracer::language_json());
}

// Keeps the picture at `path` (RGBA bytes from the top row, as a canvas gives them) for image patterns.
void provide_picture(const std::string& path, int width, int height, const emscripten::val& rgba) {
    const std::vector<unsigned char> bytes = emscripten::convertJSArrayToNumberVector<unsigned char>(rgba);
    if (width <= 0 || height <= 0 || bytes.size() != size_t(width) * size_t(height) * 4) return;
    tracer::Texels texels;
    texels.width = width, texels.height = height, texels.channels = 3;
    texels.bytes.resize(size_t(width) * size_t(height) * 3);
    for (size_t texel = 0; texel < texels.bytes.size() / 3; ++texel)
        std::copy_n(&bytes[texel * 4], 3, &texels.bytes[texel * 3]);
    tracer::provide_picture(path, std::move(texels));
}

}  // namespace

EMSCRIPTEN_BINDINGS(tracer) {
    emscripten::class_<Playground>("Playground")
        .constructor<>()
        .function("load", &Playground::load)
        .function("start", &Playground::start)
        .function("renderRows", &Playground::render_rows)
        .function("pixels", &Playground::pixels);
    emscripten::function("language", &language);
    emscripten::function("providePicture", &provide_picture);
}
