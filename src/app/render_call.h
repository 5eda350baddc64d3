// One render of a loaded scene as a library call (the Python module's): the command line's
// overrides checked by its own rules, the pixels as floats into the caller's buffer (no image of
// doubles beside them), and the caller asked now and then whether to go on (Ctrl-C).
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "app/load_files.h"
#include "render/renderer.h"

namespace tracer {

// How often a render under way asks its caller whether to go on.
constexpr std::chrono::milliseconds kSignalLook{20};

class RenderCall {
public:
    // The render of `loaded` with `overrides` (KEY, TEXT: the command line's --KEY TEXT, as
    // width, samples, adaptive, max_depth, accel, leaf_size, encoding), on `threads` (0: every
    // core), of `region` (X0, Y0, W, H; empty: the frame). std::invalid_argument says why not.
    RenderCall(std::shared_ptr<const LoadedScene> loaded,
               const std::vector<std::pair<std::string, std::string>>& overrides, int threads,
               const std::vector<int>& region);

    int width() const { return area_.width; }
    int height() const { return area_.height; }
    // A buffer for the pixels, width x height x 3 floats, row 0 at the top (new[]: the caller
    // frees it with delete[]); run() renders into it.
    float* allocate();
    // Builds the world and renders into the buffer on a thread of its own, calling `keep_going`
    // on this one every kSignalLook; false if it said stop (the render then cancelled and waited
    // for). What the build or the render throws is thrown here.
    bool run(const std::function<bool()>& keep_going);
    // The statistics of the finished render (tracer --stats-json's figures), as JSON text.
    const std::string& stats_json() const { return stats_json_; }

private:
    std::shared_ptr<const LoadedScene> loaded_;
    SceneDescription scene_;
    int threads_;
    PixelRect area_;
    float* pixels_ = nullptr;
    std::string stats_json_;
};

}  // namespace tracer
