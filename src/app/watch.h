// tracer --watch: render, then render again whenever a file the scene reads changes.
#pragma once

#include <atomic>
#include <functional>
#include <optional>
#include <string>

#include "app/load_files.h"

namespace tracer {

struct WatchSettings {
    std::string scene;
    std::string output;
    int threads = 0;
    bool quiet = false;
    bool json_events = false;                        // events as JSON lines on stdout, not text on stderr
    const std::atomic<bool>* interrupted = nullptr;  // set by Ctrl-C: stop
};

// Loads the scene with the command line's overrides, handing its diagnostics to the report.
using LoadForWatch = std::function<std::optional<LoadedScene>(const ReportLoad&)>;
// Why the output would replace one of the scene's inputs, or nullopt.
using OutputClash = std::function<std::optional<std::string>(const SceneDescription&)>;

// Loads and renders (a quick preview, then the full image), then waits for a change to the scene,
// a file it includes or a mesh, and starts again, until interrupted. A change during a render
// cancels it; a burst of changes is taken as one; a scene with errors keeps the last image.
// Returns the exit code (130 when interrupted; 3 when files cannot be watched).
int watch_scene(const WatchSettings& settings, const LoadForWatch& load, const OutputClash& output_clash);

}  // namespace tracer
