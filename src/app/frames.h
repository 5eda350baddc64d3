// Animation on the command line: which frames to make (--frames, --clock, --cyclic, --subset),
// each frame's clock (lang's FrameTime), numbered output names, and the loop that renders the
// frames in one process: the scene compiled once (SceneProgram), its mesh files read and their
// BVHs built once (FileCache, MeshBuildCache), each frame written atomically, a run resumed.
#pragma once

#include <atomic>
#include <functional>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "app/load_files.h"
#include "lang/interpreter.h"
#include "render/renderer.h"

namespace tracer {

// The most frames one animation may have (over 11 hours at 24 frames a second).
constexpr int kMostFrames = 1'000'000;

struct FrameRange {
    int count = 0;                           // --frames N: frames 0 .. N - 1 (0: a still image)
    double first_clock = 0, last_clock = 1;  // --clock A:B, the clock at frame 0 and at frame N - 1
    bool cyclic = false;       // --cyclic: frame N would be frame 0 again (the clock at N - 1 falls short of B)
    int first = 0, last = -1;  // --subset F[:L]: the frames made, both ends included (-1: the last)
    bool resume = false;       // --resume: a frame whose file is there, whole, is not made again

    bool animated() const { return count > 0; }
    int last_made() const { return last < 0 ? count - 1 : last; }
    int frames_made() const { return last_made() - first + 1; }
};

// The clock of frame `frame` (all 0 for a still image): clock = lerp(A, B, frame / (N - 1)), or
// frame / N when cyclic; clock_delta the step between frames (0 for one frame, not cyclic).
FrameTime frame_time(const FrameRange& range, int frame);

// --clock's A:B read into `range`; the problem if it is not two finite numbers.
std::optional<std::string> read_clock_range(const std::string& text, FrameRange& range);
// --subset's F or F:L read into `range`; the problem if they are not whole numbers, F <= L.
std::optional<std::string> read_subset(const std::string& text, FrameRange& range);
// Why the range cannot be made (a subset outside the frames), or nullopt.
std::optional<std::string> frame_range_problem(const FrameRange& range);

// True if `pattern`'s file name has a number field: a run of '#'.
bool has_number_field(const std::string& pattern);
// `pattern` with its file name's last run of '#' replaced by `frame`, zero-padded to the run's
// length (more digits if the number needs them): frames/orbit_###.png, 7 -> frames/orbit_007.png.
std::string frame_path(const std::string& pattern, int frame);

// What the frame loop needs from the command line.
struct AnimationJob {
    FrameRange range;
    std::string output;  // the pattern
    int threads = 0;
    bool quiet = false;
    PixelRect crop;  // --region (width 0: the whole frame)
    const std::atomic<bool>* cancel = nullptr;
    // The scene at one frame, adjusted by the command line, with its files (from `files`);
    // nullopt with the diagnostics reported. `first` says whether it is the first frame loaded.
    std::function<std::optional<LoadedScene>(SceneProgram&, const FrameTime&, FileCache&, bool first)> load;
    // Why the frame's output path cannot be written for this scene (a clash with an input), or nullopt.
    std::function<std::optional<std::string>(const std::string& path, const SceneDescription&)> output_problem;
};

enum class AnimationEnd { Done, SceneError, WriteError, UsageError, Interrupted };

// What the frames of one process share however many runs of them it renders (--frame-list):
// the mesh and image files read, the meshes' BVHs.
struct AnimationCaches {
    FileCache files;
    MeshBuildCache builds;
};

// Renders the frames of `job.range` to their files in order, with `program` (the scene, run once
// per frame); a line per frame on stderr unless quiet; `figures` gets the run's statistics (per
// frame, and the compilations, mesh files read and BVHs built). Stops at the first frame that
// fails, with its message on stderr; every frame written before it stays.
AnimationEnd render_animation(const AnimationJob& job, SceneProgram& program, nlohmann::ordered_json& figures);
// The same with the caches of earlier runs.
AnimationEnd render_animation(const AnimationJob& job, SceneProgram& program, nlohmann::ordered_json& figures,
                              AnimationCaches& caches);

}  // namespace tracer
