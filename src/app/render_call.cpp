#include "app/render_call.h"

#include <condition_variable>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "app/options.h"
#include "app/regions.h"
#include "lang/validate.h"
#include "render/render_stats.h"

namespace tracer {

RenderCall::RenderCall(std::shared_ptr<const LoadedScene> loaded,
                       const std::vector<std::pair<std::string, std::string>>& overrides, int threads,
                       const std::vector<int>& region)
    : loaded_(std::move(loaded)), scene_(loaded_->scene), threads_(threads) {
    // Step 1: the overrides, each checked as the command line checks its option.
    Options options;
    for (const auto& [key, value] : overrides) {
        std::string* field = override_field(options, key);
        if (!field) throw std::invalid_argument("unknown render setting '" + key + "'");
        std::string text = value;
        if (std::string problem = override_problem(key, text); !problem.empty())
            throw std::invalid_argument(key + ": " + problem);
        *field = text;
    }
    apply_overrides(options, scene_);
    if (const std::string problem = render_settings_problem(scene_.render); !problem.empty())
        throw std::invalid_argument(problem);
    // Step 2: the pixels asked for.
    if (threads < 0) throw std::invalid_argument("threads must be 0 (every core) or more");
    if (!region.empty()) {
        if (auto problem = region_problem(region, scene_.render)) throw std::invalid_argument(*problem);
        area_ = {region[0], region[1], region[2], region[3]};
    } else {
        area_ = {0, 0, scene_.render.width, scene_.render.height};
    }
}

float* RenderCall::allocate() {
    pixels_ = new float[size_t(area_.width) * size_t(area_.height) * 3];
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
            const World world(scene_, loaded_->meshes, threads_);
            RenderOptions options;
            options.threads = threads_;
            options.crop = area_;
            options.cancel = &cancel;
            options.float_pixels = pixels_;
            Image image;
            RenderStats stats;
            if (render(world, scene_, options, image, stats))
                stats_json_ = render_stats_json(world, scene_, stats)
                                  .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
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
