// The fuzz targets' last stage: a scene rendered at 8 x 8 pixels, one sample, shallow
// recursion, one thread, so every input also goes through the world, the BVHs and shading
// quickly. A render's cost is the scene's by design (a 256 x 256 area light over 2,000
// transparent spheres takes seconds even at 8 x 8; the limits that bound it are tested in
// tests/cli): past kRenderDeadline the render is cancelled as Ctrl-C would, so the fuzzer's time
// goes to new inputs, and only code that ignores the cancel flag (a real hang) reaches its timeout.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "accel/world.h"
#include "base/image.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace tracer {

constexpr std::chrono::seconds kRenderDeadline{1};

inline void render_small(SceneDescription scene, const SceneMeshes& meshes) {
    scene.render.width = 8;
    scene.render.height = 8;
    scene.render.samples = 1;
    scene.render.max_depth = std::min(scene.render.max_depth, 3);
    const World world(scene, meshes, 1);
    // Step 1: a watchdog that sets `cancel` at the deadline unless the render ended first.
    std::atomic<bool> cancel{false};
    std::mutex guard;
    std::condition_variable ended;
    bool done = false;
    std::thread watchdog([&] {
        std::unique_lock lock(guard);
        if (!ended.wait_for(lock, kRenderDeadline, [&] { return done; })) cancel = true;
    });
    // Step 2: the render.
    RenderOptions options;
    options.threads = 1;
    options.cancel = &cancel;
    Image image;
    RenderStats stats;
    render(world, scene, options, image, stats);
    {
        const std::lock_guard lock(guard);
        done = true;
    }
    ended.notify_one();
    watchdog.join();
}

}  // namespace tracer
