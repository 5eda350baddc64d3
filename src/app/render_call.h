// One render of a loaded scene as a library call (the Python module's): the command line's
// overrides checked by its own rules, the pixels as floats into the caller's buffer (no image of
// doubles beside them), and the caller asked now and then whether to go on (Ctrl-C).
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "accel/world.h"
#include "app/load_files.h"
#include "render/renderer.h"

namespace tracer {

// How often a render under way asks its caller whether to go on.
constexpr std::chrono::milliseconds kSignalLook{20};

using RenderOverrides = std::vector<std::pair<std::string, std::string>>;

// The world last built of one loaded scene, kept for its next renders with the same
// accelerator settings (a farm's tiles, a notebook's re-renders build it once), and the scene
// with the last overrides applied (a tile's render copies no description); thread-safe.
class WorldCache {
public:
    // `loaded` with `overrides` (checked, as the command line's options) applied, copied from
    // `loaded` only when they differ from the last call's.
    std::shared_ptr<const SceneDescription> scene_for(const SceneDescription& loaded, const RenderOverrides& overrides);
    // The world of `scene` (the loaded scene with a render's overrides) and `meshes`, built on
    // `threads` threads unless the last one built has the same accelerator and leaf size.
    std::shared_ptr<const World> world_for(const SceneDescription& scene, const SceneMeshes& meshes, int threads);

private:
    std::mutex guard_;
    std::shared_ptr<const SceneDescription> scene_;
    RenderOverrides overrides_;
    std::shared_ptr<const World> world_;
    Accelerator accel_ = Accelerator::Sah;
    int leaf_size_ = 0;
};

class RenderCall {
public:
    // The render of `loaded` with `overrides` (KEY, TEXT: the command line's --KEY TEXT, as
    // width, samples, adaptive, max_depth, accel, leaf_size, encoding), on `threads` (0: every
    // core), of `region` (X0, Y0, W, H; empty: the frame), its world taken from `worlds`; the
    // pixels as floats, or with `eight_bit` as the bytes of an 8-bit file of that encoding (rounded
    // from the renderer's doubles, as the command line's files are). std::invalid_argument says
    // why not.
    RenderCall(std::shared_ptr<const LoadedScene> loaded, std::shared_ptr<WorldCache> worlds,
               const RenderOverrides& overrides, int threads, const std::vector<int>& region,
               std::optional<Encoding> eight_bit = std::nullopt);

    int width() const { return area_.width; }
    int height() const { return area_.height; }
    // A buffer for the pixels, width x height x 3 floats (or bytes), row 0 at the top (new[] of
    // that type: the caller frees it with delete[]); run() renders into it.
    void* allocate();
    // Builds the world (unless `worlds` holds it) and renders into the buffer on a thread of its own, calling
    // `keep_going` on this one every kSignalLook; false if it said stop (the render then cancelled and waited for).
    // What the build or the render throws is thrown here.
    bool run(const std::function<bool()>& keep_going);
    // The statistics of the finished render (tracer --stats-json's figures), as JSON text.
    const std::string& stats_json() const { return stats_json_; }

private:
    std::shared_ptr<const LoadedScene> loaded_;
    std::shared_ptr<WorldCache> worlds_;
    std::shared_ptr<const SceneDescription> scene_;
    int threads_;
    PixelRect area_;
    std::optional<Encoding> eight_bit_;
    void* pixels_ = nullptr;
    std::string stats_json_;
};

}  // namespace tracer
