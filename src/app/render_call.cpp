#include "app/render_call.h"

#include <condition_variable>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "app/options.h"
#include "app/regions.h"
#include "io/native_images.h"
#include "lang/validate.h"
#include "render/render_stats.h"

namespace tracer {

std::shared_ptr<const World> WorldCache::world_for(const SceneDescription& scene, const SceneMeshes& meshes,
                                                   int threads) {
    const std::lock_guard lock(guard_);  // a second render waits for the first one's build
    if (!world_ || accel_ != scene.render.accel || leaf_size_ != scene.render.leaf_size) {
        world_.reset();  // the old world's memory back before the new one's build
        world_ = std::make_shared<const World>(scene, meshes, threads);
        accel_ = scene.render.accel;
        leaf_size_ = scene.render.leaf_size;
    }
    return world_;
}

std::shared_ptr<const SceneDescription> WorldCache::scene_for(const SceneDescription& loaded,
                                                              const RenderOverrides& overrides) {
    {
        const std::lock_guard lock(guard_);
        if (scene_ && overrides_ == overrides) return scene_;
    }
    // Each override checked as the command line checks its option, then applied to a copy.
    Options options;
    for (const auto& [key, value] : overrides) {
        std::string* field = override_field(options, key);
        if (!field) throw std::invalid_argument("unknown render setting '" + key + "'");
        std::string text = value;
        if (std::string problem = override_problem(key, text); !problem.empty())
            throw std::invalid_argument(key + ": " + problem);
        *field = text;
    }
    auto scene = std::make_shared<SceneDescription>(loaded);
    apply_overrides(options, *scene);
    if (const std::string problem = render_settings_problem(scene->render); !problem.empty())
        throw std::invalid_argument(problem);
    const std::lock_guard lock(guard_);
    scene_ = scene;
    overrides_ = overrides;
    return scene_;
}

RenderCall::RenderCall(std::shared_ptr<const LoadedScene> loaded, std::shared_ptr<WorldCache> worlds,
                       const RenderOverrides& overrides, int threads, const std::vector<int>& region,
                       std::optional<Encoding> eight_bit)
    : loaded_(std::move(loaded)), worlds_(std::move(worlds)), threads_(threads), eight_bit_(eight_bit) {
    // Step 1: the scene with the overrides (the last render's, when they are the same).
    scene_ = worlds_->scene_for(loaded_->scene, overrides);
    // Step 2: the pixels asked for.
    if (threads < 0) throw std::invalid_argument("threads must be 0 (every core) or more");
    if (!region.empty()) {
        if (auto problem = region_problem(region, scene_->render)) throw std::invalid_argument(*problem);
        area_ = {region[0], region[1], region[2], region[3]};
    } else {
        area_ = {0, 0, scene_->render.width, scene_->render.height};
    }
}

void* RenderCall::allocate() {
    const size_t values = size_t(area_.width) * size_t(area_.height) * 3;
    pixels_ = eight_bit_ ? static_cast<void*>(new unsigned char[values]) : static_cast<void*>(new float[values]);
    return pixels_;
}

bool RenderCall::run(const std::function<bool()>& keep_going) {
    std::atomic<bool> cancel{false};
    std::mutex guard;
    std::condition_variable ended;
    bool done = false;
    std::exception_ptr failure;
    // Step 1: the build and the render on a thread of their own.
    std::thread worker([&] {
        try {
            // The world the command line builds (it releases the flat shapes' lists as it goes;
            // the scene here stays whole for the next render).
            const std::shared_ptr<const World> world = worlds_->world_for(*scene_, loaded_->meshes, threads_);
            RenderOptions options;
            options.threads = threads_;
            options.crop = area_;
            options.cancel = &cancel;
            if (!eight_bit_) options.float_pixels = static_cast<float*>(pixels_);
            Image image;
            RenderStats stats;
            if (render(*world, *scene_, options, image, stats)) {
                if (eight_bit_)
                    eight_bit_rows(image, *eight_bit_ == Encoding::Srgb, static_cast<unsigned char*>(pixels_));
                stats_json_ = render_stats_json(*world, *scene_, stats)
                                  .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
            }
        } catch (...) {
            failure = std::current_exception();
        }
        const std::lock_guard lock(guard);
        done = true;
        ended.notify_one();
    });
    // Step 2: the caller asked every kSignalLook whether to go on.
    bool stopped = false;
    {
        std::unique_lock lock(guard);
        while (!ended.wait_for(lock, kSignalLook, [&] { return done; }))
            if (!stopped) {
                lock.unlock();
                stopped = !keep_going();
                lock.lock();
                if (stopped) cancel = true;
            }
    }
    worker.join();
    if (failure) std::rethrow_exception(failure);
    return !stopped;
}

}  // namespace tracer
