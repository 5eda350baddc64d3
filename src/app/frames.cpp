#include "app/frames.h"

#include <charconv>
#include <cmath>
#include <iostream>
#include <thread>

#include "app/progress.h"
#include "app/summary.h"
#include "io/image_file.h"
#include "io/native_images.h"
#include "render/render_stats.h"

namespace tracer {
namespace {

// `text` as one finite number, wholly.
std::optional<double> finite_number(std::string_view text) {
    double value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) return std::nullopt;
    return value;
}

// `text` as one whole number from 0 to kMostFrames, wholly.
std::optional<int> frame_number(std::string_view text) {
    int value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size() || value < 0 || value > kMostFrames)
        return std::nullopt;
    return value;
}

// Where the file name's last run of '#' begins in `pattern`, and its length (0 if none).
std::pair<size_t, size_t> number_field(const std::string& pattern) {
    const size_t slash = pattern.rfind('/');
    const size_t name = slash == std::string::npos ? 0 : slash + 1;
    const size_t last = pattern.rfind('#');
    if (last == std::string::npos || last < name) return {0, 0};
    size_t first = last;
    while (first > name && pattern[first - 1] == '#') --first;
    return {first, last - first + 1};
}

// Writes one frame's file on a thread of its own while the next frame is made (its PNG's encoding
// took 40% of a small frame's time), one frame at a time; finish() waits for it.
class FrameWriter {
public:
    ~FrameWriter() { finish(); }
    // Starts writing `image` to `path`; `line` is said once it is written (unless empty).
    void start(int frame, std::string path, Image image, Encoding encoding, std::string line) {
        finish();
        frame_ = frame;
        line_ = std::move(line);
        thread_ = std::thread([this, path = std::move(path), image = std::move(image), encoding] {
            problem_ = write_image(path, image, encoding);
        });
    }
    // Waits for the frame being written: false, with the message said, if it could not be.
    bool finish() {
        if (!thread_.joinable()) return true;
        thread_.join();
        if (problem_) {
            std::cerr << "tracer: error: " << *problem_ << " (frame " << frame_
                      << "; the frames before it are written)\n";
            problem_.reset();
            return false;
        }
        if (!line_.empty()) std::cerr << line_ << '\n';
        ++written_;
        return true;
    }
    // How many frames it wrote.
    int written() const { return written_; }

private:
    std::thread thread_;
    int written_ = 0;
    int frame_ = 0;
    std::string line_;
    std::optional<std::string> problem_;
};

}  // namespace

FrameTime frame_time(const FrameRange& range, int frame) {
    if (!range.animated()) return {};
    const int steps = range.cyclic ? range.count : range.count - 1;
    const double span = range.last_clock - range.first_clock;
    FrameTime time;
    time.frame_number = frame;
    time.clock = steps == 0 ? range.first_clock : std::lerp(range.first_clock, range.last_clock, double(frame) / steps);
    time.clock_delta = steps == 0 ? 0 : span / steps;
    return time;
}

std::optional<std::string> read_clock_range(const std::string& text, FrameRange& range) {
    const size_t colon = text.find(':');
    const auto first = finite_number(std::string_view(text).substr(0, colon));
    const auto last =
        colon == std::string::npos ? std::nullopt : finite_number(std::string_view(text).substr(colon + 1));
    if (!first || !last)
        return "expected FIRST:LAST, two finite numbers: the clock at the first and the last frame (e.g. 0:1)";
    range.first_clock = *first;
    range.last_clock = *last;
    return std::nullopt;
}

std::optional<std::string> read_subset(const std::string& text, FrameRange& range) {
    const size_t colon = text.find(':');
    const auto first = frame_number(std::string_view(text).substr(0, colon));
    const auto last = colon == std::string::npos ? first : frame_number(std::string_view(text).substr(colon + 1));
    if (!first || !last || *last < *first)
        return "expected FIRST or FIRST:LAST, frame numbers from 0 with FIRST <= LAST (both are made), e.g. 3 or 0:7";
    range.first = *first;
    range.last = *last;
    return std::nullopt;
}

std::optional<std::string> frame_range_problem(const FrameRange& range) {
    if (range.last_made() >= range.count)
        return "--subset " + std::to_string(range.first) + ":" + std::to_string(range.last_made()) +
               " is outside the animation's frames 0 to " + std::to_string(range.count - 1) + " (--frames " +
               std::to_string(range.count) + ")";
    return std::nullopt;
}

bool has_number_field(const std::string& pattern) {
    return number_field(pattern).second > 0;
}

std::string frame_path(const std::string& pattern, int frame) {
    const auto [at, length] = number_field(pattern);
    if (length == 0) return pattern;
    std::string number = std::to_string(frame);
    if (number.size() < length) number.insert(0, length - number.size(), '0');
    return pattern.substr(0, at) + number + pattern.substr(at + length);
}

AnimationEnd render_animation(const AnimationJob& job, SceneProgram& program, nlohmann::ordered_json& figures) {
    AnimationCaches caches;
    return render_animation(job, program, figures, caches);
}

AnimationEnd render_animation(const AnimationJob& job, SceneProgram& program, nlohmann::ordered_json& figures,
                              AnimationCaches& caches) {
    FileCache& files = caches.files;
    MeshBuildCache& builds = caches.builds;
    FrameWriter writer;
    nlohmann::ordered_json frames = nlohmann::ordered_json::array();
    int kept = 0;
    // The run's figures, once the frame being written is (false if it failed: said by finish).
    auto summarise = [&] {
        const bool written = writer.finish();
        figures["frames"] = frames;
        figures["frames_rendered"] = writer.written();
        figures["frames_kept"] = kept;
        figures["scene_compilations"] = program.compilations();
        figures["mesh_files_read"] = files.meshes.size();
        figures["mesh_builds"] = builds.builds();
        return written;
    };
    const FrameRange& range = job.range;
    for (int frame = range.first; frame <= range.last_made(); ++frame) {
        if (job.cancel && *job.cancel) return summarise(), AnimationEnd::Interrupted;
        // Step 1: the scene at this frame's clock; a frame already made is kept.
        const FrameTime time = frame_time(range, frame);
        const std::string path = frame_path(job.output, frame);
        auto loaded = job.load(program, time, files, frame == range.first);
        if (!loaded) {
            std::cerr << "tracer: error: frame " << frame << " (clock " << time.clock << ") has errors; nothing of it "
                      << "written" << (frame > range.first ? ", the frames before it are" : "") << '\n';
            return summarise(), AnimationEnd::SceneError;
        }
        SceneDescription& scene = loaded->scene;
        if (auto problem = job.output_problem(path, scene)) {
            std::cerr << "tracer: error: " << *problem << '\n';
            return summarise(), AnimationEnd::UsageError;
        }
        const int width = job.crop.width > 0 ? job.crop.width : scene.render.width;
        const int height = job.crop.width > 0 ? job.crop.height : scene.render.height;
        if (range.resume && image_file_is_whole(path, width, height)) {
            ++kept;
            frames.push_back({{"frame", frame}, {"clock", time.clock}, {"output", path}, {"kept", true}});
            if (!job.quiet) std::cerr << "frame " << frame << ": " << path << " is there, whole: kept\n";
            continue;
        }
        // Step 2: the world (only its top level new, once the meshes are built), the render.
        const World world(scene, loaded->meshes, job.threads, World::ReleaseFlatShapes{}, builds);
        ProgressLine progress(!job.quiet);
        RenderOptions options;
        options.threads = job.threads;
        options.crop = job.crop;
        options.cancel = job.cancel;
        options.progress = [&](double fraction) { progress.update(fraction); };
        Image image;
        RenderStats stats;
        const bool complete = render(world, scene, options, image, stats);
        progress.finish();
        if (!complete || (job.cancel && *job.cancel)) return summarise(), AnimationEnd::Interrupted;
        // Step 3: the file, atomically, on the writer's thread once the frame before is written.
        if (!writer.finish()) return summarise(), AnimationEnd::WriteError;
        nlohmann::ordered_json figure = {{"frame", frame}, {"clock", time.clock}, {"output", path}};
        figure.update(render_stats_json(world, scene, stats));
        frames.push_back(std::move(figure));
        std::string line =
            job.quiet ? "" : "frame " + std::to_string(frame) + ": " + render_summary(path, image, scene.render, stats);
        writer.start(frame, path, std::move(image), scene.render.encoding, std::move(line));
    }
    return summarise() ? AnimationEnd::Done : AnimationEnd::WriteError;
}

}  // namespace tracer
