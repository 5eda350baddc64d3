#include "app/watch.h"

#include <poll.h>
#include <sys/inotify.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <mutex>
#include <set>
#include <thread>

#include "app/diagnostics_json.h"
#include "app/summary.h"
#include "base/parallel.h"
#include "io/image_file.h"
#include "render/renderer.h"

namespace tracer {
namespace {

using Clock = std::chrono::steady_clock;

// The image is rendered small first (this fraction of each side, one sample, depth at most 2)
// unless the full image is about as quick: at most this many samples.
constexpr int kPreviewDivisor = 4;
constexpr int kPreviewDepth = 2;
constexpr long kNoPreviewUpTo = 256 * 256;
// A burst of saves is one change: the load waits until none came for this long.
constexpr auto kQuietBeforeLoad = std::chrono::milliseconds(40);

// The path inotify reports for `file`: absolute, symbolic links of its folders resolved.
std::string watched_path(const std::string& file) {
    std::error_code error;
    std::filesystem::path path = std::filesystem::weakly_canonical(std::filesystem::absolute(file, error), error);
    if (error) path = std::filesystem::absolute(file, error).lexically_normal();
    return path.string();
}

// Changes to a set of files, seen through inotify: each file's folder is watched (editors save
// by writing a new file and renaming it over the old one) and events are filtered by name.
class FileWatcher {
public:
    FileWatcher() : fd_(inotify_init1(IN_NONBLOCK | IN_CLOEXEC)) {}
    ~FileWatcher() {
        if (fd_ >= 0) ::close(fd_);
    }
    FileWatcher(const FileWatcher&) = delete;
    FileWatcher& operator=(const FileWatcher&) = delete;

    // Why files cannot be watched, or "".
    std::string problem() const { return fd_ < 0 ? std::string("inotify: ") + std::strerror(errno) : ""; }

    // Watches exactly `files` from now on; a file in both the old and the new set is watched
    // throughout, so no change to it is missed while the set is replaced.
    void watch(const std::vector<std::string>& files) {
        std::set<std::string> paths, folders;
        for (const std::string& file : files) {
            const std::string path = watched_path(file);
            paths.insert(path);
            folders.insert(std::filesystem::path(path).parent_path().string());
        }
        std::lock_guard lock(mutex_);
        for (const std::string& folder : folders)
            if (!folder_of_.count(folder)) {
                const int wd = inotify_add_watch(fd_, folder.c_str(),
                                                 IN_CLOSE_WRITE | IN_MOVED_TO | IN_CREATE | IN_DELETE | IN_MOVED_FROM);
                if (wd >= 0) {
                    folder_of_[folder] = wd;
                    folders_[wd] = folder;
                }
            }
        for (auto it = folder_of_.begin(); it != folder_of_.end();)
            if (!folders.count(it->first)) {
                inotify_rm_watch(fd_, it->second);
                folders_.erase(it->second);
                it = folder_of_.erase(it);
            } else {
                ++it;
            }
        files_ = std::move(paths);
    }

    // Waits up to `timeout_ms` for events; the path of a watched file that changed, or "".
    std::string changed(int timeout_ms) {
        pollfd ready{fd_, POLLIN, 0};
        if (::poll(&ready, 1, timeout_ms) <= 0) return "";
        std::lock_guard lock(mutex_);
        std::string hit;
        alignas(inotify_event) char buffer[16384];
        for (ssize_t n; (n = ::read(fd_, buffer, sizeof buffer)) > 0;)
            for (char* at = buffer; at < buffer + n;) {
                const auto* event = reinterpret_cast<const inotify_event*>(at);
                at += sizeof(inotify_event) + event->len;
                if (event->mask & IN_Q_OVERFLOW) hit = "(many files)";
                const auto folder = folders_.find(event->wd);
                if (event->len == 0 || folder == folders_.end()) continue;
                const std::string path = folder->second + "/" + event->name;
                if (files_.count(path)) hit = path;
            }
        return hit;
    }

private:
    int fd_;
    std::mutex mutex_;
    std::map<int, std::string> folders_;    // by watch descriptor
    std::map<std::string, int> folder_of_;  // the watch descriptor of a folder
    std::set<std::string> files_;
};

// Which image of a change a render makes: the quick preview, or the full image.
enum class Stage { Preview, Full };

// The stage's name in the JSON events ("preview", "full").
const char* stage_name(Stage stage) {
    return stage == Stage::Preview ? "preview" : "full";
}

// What the user sees: text on stderr, or one JSON object per line on stdout.
class WatchEvents {
public:
    explicit WatchEvents(const WatchSettings& settings) : settings_(settings) {}

    // A load: its diagnostics, and when it failed, that the last image stays.
    void loaded(const std::string& scene, const LoadReport& report) const {
        if (settings_.json_events) {
            nlohmann::json event = load_report_json(scene, report);
            event["event"] = "load";
            emit(event);
        } else {
            report.diagnostics.print(std::cerr);
            if (report.diagnostics.has_errors())
                std::cerr << "tracer: " << (wrote_ ? "the last good image stays in '" + settings_.output + "'; " : "")
                          << "waiting for a change (Ctrl-C stops)\n";
        }
    }
    // An image written: its summary line ("preview" or "full"), and the note when camera rays
    // reached the bound of their ray trees.
    void image(Stage stage, const std::string& summary, const Image& image, const RenderSettings& full,
               const RenderStats& stats) {
        wrote_ = true;
        const std::string note = trees_cut_note(stats);  // the image is not what max_depth says
        if (settings_.json_events) {
            emit({{"event", "image"},
                  {"stage", stage_name(stage)},
                  {"path", settings_.output},
                  {"width", image.width},
                  {"height", image.height},
                  {"full_width", full.width},
                  {"full_height", full.height},
                  {"seconds", stats.seconds},
                  {"summary", summary},
                  {"trees_cut", stats.rays.trees_cut},
                  {"note", note}});
            return;
        }
        if (!settings_.quiet) std::cerr << summary << (stage == Stage::Preview ? " (preview)" : "") << '\n';
        if (!note.empty() && stage == Stage::Full) std::cerr << note << '\n';  // even with --quiet
    }
    // A problem outside the scene (an output that clashes with an input, a failed write).
    void problem(const std::string& message) const {
        if (settings_.json_events)
            emit({{"event", "error"}, {"message", message}});
        else
            std::cerr << "tracer: error: " << message << '\n';
    }
    // A change seen: the first file that changed, and whether it cut a round short.
    void changed(const std::string& path, bool cancelled) const {
        if (settings_.json_events)
            emit({{"event", "changed"}, {"path", path}, {"cancelled_render", cancelled}});
        else if (!settings_.quiet)
            std::cerr << "tracer: " << path << " changed; " << (cancelled ? "render cancelled, " : "")
                      << "loading again\n";
    }

private:
    static void emit(const nlohmann::json& event) { std::cout << json_line(event) << std::flush; }
    const WatchSettings& settings_;
    bool wrote_ = false;
};

// Watches in a thread of its own: a change makes the current work stale and cancels its render;
// Ctrl-C cancels it too.
class ChangeListener {
public:
    ChangeListener(FileWatcher& watcher, const std::atomic<bool>* interrupted)
        : watcher_(watcher), interrupted_(interrupted), thread_([this] { listen(); }) {}
    ~ChangeListener() {
        done_ = true;
        thread_.join();
    }
    // Starts a new round of work: nothing is stale.
    void start_round() {
        std::lock_guard lock(mutex_);
        stale_ = false;
        cancel_ = false;
        changed_path_.clear();
    }
    bool stale() const { return stale_; }
    const std::atomic<bool>* cancel() const { return &cancel_; }
    std::string changed_path() {
        std::lock_guard lock(mutex_);
        return changed_path_;
    }
    Clock::time_point last_change() {
        std::lock_guard lock(mutex_);
        return last_change_;
    }

private:
    void listen() {
        while (!done_) {
            const std::string path = watcher_.changed(10);
            if (interrupted_ && *interrupted_) cancel_ = true;
            if (path.empty()) continue;
            std::lock_guard lock(mutex_);
            if (changed_path_.empty()) changed_path_ = path;
            last_change_ = Clock::now();
            stale_ = true;
            cancel_ = true;
        }
    }

    FileWatcher& watcher_;
    const std::atomic<bool>* interrupted_;
    std::mutex mutex_;
    std::atomic<bool> stale_{false}, cancel_{false}, done_{false};
    std::string changed_path_;
    Clock::time_point last_change_ = Clock::now();
    std::thread thread_;
};

// Renders `scene` with `settings_used` and writes the image: false if cancelled or failed.
bool render_and_write(const World& world, SceneDescription& scene, const RenderSettings& settings_used, Stage stage,
                      const ChangeListener& listener, const WatchSettings& settings, WatchEvents& events) {
    const RenderSettings full = scene.render;
    scene.render = settings_used;
    RenderOptions options;
    options.threads = settings.threads;
    options.cancel = listener.cancel();
    Image image;
    RenderStats stats;
    const bool complete = tracer::render(world, scene, options, image, stats);
    const std::string summary = render_summary(settings.output, image, scene.render, stats);
    scene.render = full;
    if (!complete) return false;
    if (auto problem = write_image(settings.output, image, full.encoding)) {
        events.problem(*problem);
        return false;
    }
    events.image(stage, summary, image, full, stats);
    return true;
}

// The preview's settings: a fraction of the size, one sample, a shallow ray tree.
RenderSettings preview_of(const RenderSettings& full) {
    RenderSettings preview = full;
    preview.width = std::max(1, full.width / kPreviewDivisor);
    preview.height = std::max(1, full.height / kPreviewDivisor);
    preview.samples = 1;
    preview.antialias = Antialias::Uniform;
    preview.max_depth = std::min(full.max_depth, kPreviewDepth);
    return preview;
}

}  // namespace

int watch_scene(const WatchSettings& settings, const LoadForWatch& load, const OutputClash& output_clash) {
    FileWatcher watcher;
    if (std::string problem = watcher.problem(); !problem.empty()) {
        std::cerr << "tracer: error: cannot watch the scene's files: " << problem << '\n';
        return 3;
    }
    watcher.watch({settings.scene});
    ChangeListener listener(watcher, settings.interrupted);
    WatchEvents events(settings);
    auto interrupted = [&] { return settings.interrupted && *settings.interrupted; };
    while (!interrupted()) {
        // Step 1: load, and watch every file the load read (also when it failed).
        listener.start_round();
        auto loaded = load([&](const LoadReport& report) {
            std::vector<std::string> files = report.files_read;
            files.push_back(settings.scene);
            watcher.watch(files);
            events.loaded(settings.scene, report);
        });
        // Step 2: a preview, then the full image, unless a change made them stale.
        if (loaded && !listener.stale()) {
            if (auto clash = output_clash(loaded->scene)) {
                events.problem(*clash);
            } else {
                const World world(loaded->scene, loaded->meshes, settings.threads, World::ReleaseFlatShapes{});
                SceneDescription& scene = loaded->scene;
                const RenderSettings& full = scene.render;
                const long samples = long(full.width) * full.height * full.samples;
                const bool previewed =
                    samples <= kNoPreviewUpTo ||
                    render_and_write(world, scene, preview_of(full), Stage::Preview, listener, settings, events);
                if (previewed && !listener.stale())
                    render_and_write(world, scene, full, Stage::Full, listener, settings, events);
            }
        }
        // Step 3: wait for a change, then for a quiet moment (a burst of saves is one change).
        const bool cancelled = listener.stale();
        while (!listener.stale() && !interrupted()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
        while (!interrupted() && Clock::now() - listener.last_change() < kQuietBeforeLoad)
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        if (!interrupted()) events.changed(listener.changed_path(), cancelled);
    }
    if (!settings.quiet && !settings.json_events) std::cerr << "tracer: stopped watching\n";
    return 130;
}

}  // namespace tracer
