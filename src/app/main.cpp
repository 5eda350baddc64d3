// tracer: render a scene file, check it, or print it as resolved JSON.
// Exit codes: 0 success; 1 the scene has errors; 2 bad command line; 3 the scene file cannot
// be read, the image cannot be written or memory ran out; 130 interrupted (Ctrl-C, SIGTERM).
// Nothing is written to the output path unless the render completed, and then atomically.

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <new>

#include "app/diagnostics_json.h"
#include "app/frames.h"
#include "app/load_files.h"
#include "app/options.h"
#include "app/progress.h"
#include "app/regions.h"
#include "app/summary.h"
#include "app/watch.h"
#include "base/fast_exit.h"
#include "base/output_file.h"
#include "base/parallel.h"
#include "io/image_file.h"
#include "lang/load_scene.h"
#include "lang/reference_doc.h"
#include "lang/schema.h"
#include "lang/standard_library.h"
#include "lang/validate.h"
#include "render/render_stats.h"
#include "render/renderer.h"
#include "scene/mesh_facts.h"
#include "scene/scene_json.h"

namespace {

using tracer::Options;
using tracer::scene_name;
using tracer::standard_input_name;

enum ExitCode { kOk = 0, kSceneError = 1, kUsageError = 2, kIoError = 3, kInterrupted = 130 };

std::atomic<bool> g_interrupted{false};
std::atomic<bool> g_rendering{false};
std::atomic<bool> g_waiting_for_regions{false};

// Before the render (or between the regions of a list) nothing is being written: stop at once.
// During it: ask the render to stop (it then writes nothing). Async-signal-safe: an atomic store,
// write(2) and _exit only.
extern "C" void on_interrupt(int) {
    if (!g_rendering || g_waiting_for_regions) {
        // The same words as an interrupted render's (a region list's finished regions stay written).
        static constexpr char kLoading[] = "tracer: interrupted; nothing written\n";
        static constexpr char kBetweenRegions[] = "tracer: interrupted\n";
        const bool between = g_waiting_for_regions;
        const ssize_t ignored = between ? ::write(STDERR_FILENO, kBetweenRegions, sizeof kBetweenRegions - 1)
                                        : ::write(STDERR_FILENO, kLoading, sizeof kLoading - 1);
        (void)ignored;
        ::_exit(kInterrupted);
    }
    g_interrupted = true;
}

// Ends the process after an interrupted render, once `message` is said: nothing is being written,
// and freeing what the render held (an 8192 x 8192 image is 1.5 GiB) took most of the time from
// Ctrl-C to the exit, so a helper frees it after. Standard output is flushed first (a region
// list's answers).
[[noreturn]] void exit_interrupted(const char* message) {
    std::cout.flush();
    std::cerr << message << std::flush;
    tracer::exit_leaving_memory_to_a_helper(kInterrupted);
}

// Where the scene comes from, with the command line's -D values and include folders.
tracer::SceneInput scene_input(const Options& options) {
    return {options.scene, standard_input_name(options), {parameter_values(options), include_folders(options)}, {}};
}

// How a load's diagnostics reach the user: as text on stderr, or as one line of JSON on stdout.
tracer::ReportLoad report_for(const Options& options) {
    if (!options.json_diagnostics) return tracer::print_diagnostics_to(std::cerr);
    const std::string name = scene_name(options);
    return [name](const tracer::LoadReport& found) {
        std::cout << tracer::json_line(tracer::load_report_json(name, found)) << std::flush;
    };
}

std::optional<tracer::LoadedScene> load(const Options& options, int& exit_code, const tracer::ReportLoad& report);

// Loads and validates the scene with the command line's overrides and reads its meshes,
// reporting every diagnostic; nullopt on errors (with `exit_code` set).
std::optional<tracer::LoadedScene> load(const Options& options, int& exit_code) {
    return load(options, exit_code, report_for(options));
}

// The same, handing the diagnostics to `report`.
std::optional<tracer::LoadedScene> load(const Options& options, int& exit_code, const tracer::ReportLoad& report) {
    bool unreadable = false;
    tracer::SceneInput input = scene_input(options);
    input.arguments.frame = tracer::frame_time(options.frames, options.frames.first);  // one frame, or a still
    auto loaded = tracer::load_scene_with_meshes(
        input, [&](tracer::SceneDescription& scene) { apply_overrides(options, scene); },
        [&](const tracer::LoadReport& found) {
            unreadable = found.unreadable;
            if (report) report(found);
        });
    if (!loaded) exit_code = unreadable ? kIoError : kSceneError;
    return loaded;
}

// JSON text even when a path in it is not UTF-8 (such bytes become U+FFFD, not an abort).
std::string json_text(const nlohmann::json& value) {
    return value.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
}

// Why the paths the render will write clash with its inputs or with each other, or nullopt:
// an output must never replace the scene, a file it includes, a mesh or the other output.
std::optional<std::string> output_clash(const Options& options, const tracer::SceneDescription& scene) {
    std::vector<std::pair<std::string, std::string>> inputs = {{options.scene, "the scene file"}};
    for (const std::string& included : scene.included_paths) inputs.push_back({included, "a file the scene includes"});
    for (const tracer::Mesh& mesh : scene.meshes) inputs.push_back({mesh.path, "a mesh file"});
    for (const auto& [output, what] :
         {std::pair{options.output, "-o"}, std::pair{options.stats_json, "--stats-json"}}) {
        if (output.empty()) continue;
        for (const auto& [input, kind] : inputs)
            if (tracer::same_file(output, input))
                return std::string(what) + " '" + output + "' is " + kind + "; choose another output path";
    }
    if (!options.stats_json.empty() && tracer::same_file(options.output, options.stats_json))
        return "--stats-json and -o name the same file '" + options.output + "'";
    return std::nullopt;
}

// False, with the message said, if --stats-json's file could not be written (checked before a render).
bool stats_json_can_be_written(const Options& options) {
    if (options.stats_json.empty()) return true;
    auto problem = tracer::output_path_problem(options.stats_json);
    if (problem) std::cerr << "tracer: error: cannot write '" << options.stats_json << "': " << *problem << '\n';
    return !problem;
}

// Writes the figures to --stats-json's file, if one is given; false, with the message said, if it failed.
bool write_stats_json(const Options& options, const nlohmann::ordered_json& figures) {
    if (options.stats_json.empty()) return true;
    auto problem = tracer::write_file_atomically(options.stats_json, json_text(figures) + '\n');
    if (problem) std::cerr << "tracer: error: cannot write '" << options.stats_json << "': " << *problem << '\n';
    return !problem;
}

// --region-list: the regions read from stdin, each written where its line says.
int render_regions(const Options& options, const tracer::World& world, const tracer::SceneDescription& scene) {
    tracer::RenderOptions render_options;
    render_options.threads = options.threads;
    render_options.cancel = &g_interrupted;
    g_rendering = true;
    auto output_problem = [&](const std::string& path) -> std::optional<std::string> {
        if (auto problem = tracer::check_output_path(path)) return problem;
        Options one = options;
        one.output = path;
        return output_clash(one, scene);
    };
    const bool complete = tracer::render_region_list(world, scene, render_options, output_problem, std::cin, std::cout,
                                                     g_waiting_for_regions);
    if (!complete || g_interrupted)
        exit_interrupted("tracer: interrupted; the region being rendered was not written\n");
    return kOk;
}

int render_to_file(const Options& options) {
    // Step 1: check everything that can be checked before spending time on pixels.
    if (!options.region_list)
        if (auto problem = tracer::check_output_path(options.output)) {
            std::cerr << "tracer: error: " << *problem << '\n';
            return kIoError;
        }
    if (!stats_json_can_be_written(options)) return kIoError;
    int exit_code = kOk;
    const auto start = std::chrono::steady_clock::now();
    tracer::start_threads(options.threads);  // made while the scene loads
    auto loaded = load(options, exit_code);
    if (!loaded) return exit_code;
    const auto loaded_at = std::chrono::steady_clock::now();
    const tracer::SceneDescription& scene = loaded->scene;
    if (auto clash = output_clash(options, scene)) {
        std::cerr << "tracer: error: " << *clash << '\n';
        return kUsageError;
    }
    if (!options.region.empty())
        if (auto problem = tracer::region_problem(options.region, scene.render)) {
            std::cerr << "tracer: error: --" << *problem << '\n';
            return kUsageError;
        }
    // A frame of an animation (a region of one: tools/farm) is built as the frame loop builds it,
    // each mesh an instance, so that its pixels are the loop's.
    tracer::MeshBuildCache instanced;
    const tracer::World world =
        options.frames.animated()
            ? tracer::World(loaded->scene, loaded->meshes, options.threads, tracer::World::ReleaseFlatShapes{},
                            instanced)
            : tracer::World(loaded->scene, loaded->meshes, options.threads, tracer::World::ReleaseFlatShapes{});
    const auto built_at = std::chrono::steady_clock::now();
    if (options.region_list) return render_regions(options, world, scene);

    // Step 2: render, stoppable with Ctrl-C (or a SIGTERM, even one that came while loading).
    tracer::ProgressLine progress(!options.quiet);
    tracer::RenderOptions render_options;
    render_options.threads = options.threads;
    if (!options.region.empty())
        render_options.crop = {options.region[0], options.region[1], options.region[2], options.region[3]};
    render_options.cancel = &g_interrupted;
    render_options.progress = [&](double fraction) { progress.update(fraction); };
    tracer::Image image;
    tracer::RenderStats stats;
    g_rendering = true;
    bool complete = tracer::render(world, scene, render_options, image, stats);
    progress.finish();
    if (!complete || g_interrupted) exit_interrupted("tracer: interrupted; nothing written\n");

    // Step 3: write atomically and summarise.
    if (auto problem = tracer::write_image(options.output, image, scene.render.encoding)) {
        std::cerr << "tracer: error: " << *problem << '\n';
        return kIoError;
    }
    auto figures = tracer::render_stats_json(world, scene, stats);
    if (options.stats) std::cerr << tracer::render_stats_text(figures);
    // The two steps before the render, for benchmarks of big scenes (the figures' own
    // build_seconds time each BVH alone).
    figures["load_seconds"] = std::chrono::duration<double>(loaded_at - start).count();
    figures["world_seconds"] = std::chrono::duration<double>(built_at - loaded_at).count();
    if (!write_stats_json(options, figures)) return kIoError;
    if (!options.quiet) std::cerr << tracer::render_summary(options.output, image, scene.render, stats) << '\n';
    // Shown even with --quiet: the image is not what max_depth says.
    if (const std::string note = tracer::trees_cut_note(stats); !note.empty()) std::cerr << note << '\n';
    return kOk;
}

std::string vector_text(const tracer::dvec3& v) {
    char text[96];
    std::snprintf(text, sizeof text, "(%.6g, %.6g, %.6g)", v.x, v.y, v.z);
    return text;
}

// The frame loop's callbacks for the command line's options; `unreadable` is set when the
// scene file could not be read.
tracer::AnimationJob animation_job(const Options& options, bool& unreadable) {
    tracer::AnimationJob job;
    job.range = options.frames;
    job.output = options.output;
    job.threads = options.threads;
    job.quiet = options.quiet;
    if (!options.region.empty())
        job.crop = {options.region[0], options.region[1], options.region[2], options.region[3]};
    job.cancel = &g_interrupted;
    const tracer::ReportLoad report = report_for(options);
    job.load = [&options, &unreadable, report](tracer::SceneProgram& program, const tracer::FrameTime& time,
                                               tracer::FileCache& files, bool first) {
        // The first frame's diagnostics all; a later frame's only if it has errors (its
        // warnings are the first frame's again, most often).
        return tracer::load_frame_with_meshes(
            program, time, scene_input(options),
            [&options](tracer::SceneDescription& scene) { tracer::apply_overrides(options, scene); },
            [&, first](const tracer::LoadReport& found) {
                unreadable = found.unreadable;
                if (first || found.diagnostics.has_errors()) report(found);
            },
            files);
    };
    job.output_problem = [&options](const std::string& path,
                                    const tracer::SceneDescription& scene) -> std::optional<std::string> {
        Options one = options;
        one.output = path;
        if (auto clash = output_clash(one, scene)) return clash;
        if (!options.region.empty())
            if (auto problem = tracer::region_problem(options.region, scene.render)) return "--" + *problem;
        return std::nullopt;
    };
    return job;
}

// --frames N: the frames (even one) rendered in one process, in the frame loop.
int render_frames(const Options& options) {
    if (auto problem = tracer::check_output_path(tracer::frame_path(options.output, options.frames.first))) {
        std::cerr << "tracer: error: " << *problem << '\n';
        return kIoError;
    }
    if (!stats_json_can_be_written(options)) return kIoError;
    tracer::start_threads(options.threads);
    tracer::SceneProgram program(options.scene, scene_input(options).arguments, standard_input_name(options));
    bool unreadable = false;
    const tracer::AnimationJob job = animation_job(options, unreadable);
    g_rendering = true;  // Ctrl-C now asks the loop to stop: a frame under way is not written
    nlohmann::ordered_json figures;
    const tracer::AnimationEnd end = tracer::render_animation(job, program, figures);
    if (end == tracer::AnimationEnd::Interrupted)
        exit_interrupted("tracer: interrupted; the frame under way was not written (the frames before it are)\n");
    if (!write_stats_json(options, figures)) return kIoError;
    switch (end) {
        case tracer::AnimationEnd::Done: return kOk;
        case tracer::AnimationEnd::SceneError: return unreadable ? kIoError : kSceneError;
        case tracer::AnimationEnd::UsageError: return kUsageError;
        default: return kIoError;
    }
}

int check_only(const Options& options);

// A --frame-list request "FIRST LAST PATTERN" read into `range` and `pattern`; the problem if it is not one.
std::optional<std::string> frame_request(const std::string& line, tracer::FrameRange& range, std::string& pattern) {
    std::istringstream words(line);
    long long first = -1, last = -1;
    if (!(words >> first >> last) || first < 0 || last < first || last >= range.count)
        return "expected 'FIRST LAST PATTERN' with 0 <= FIRST <= LAST < " + std::to_string(range.count);
    words >> std::ws;
    std::getline(words, pattern);
    if (pattern.empty()) return "no output pattern after the frames";
    if (last > first && !tracer::has_number_field(pattern)) return "the pattern '" + pattern + "' has no number field";
    range.first = int(first);
    range.last = int(last);
    return tracer::check_output_path(tracer::frame_path(pattern, range.first));
}

// --frames N --frame-list: the scene compiled and its files read once, then the runs of frames
// read from standard input rendered one after the other (tools/farm's workers).
int render_frame_list(const Options& options) {
    tracer::start_threads(options.threads);
    tracer::SceneProgram program(options.scene, scene_input(options).arguments, standard_input_name(options));
    bool unreadable = false;
    tracer::AnimationJob job = animation_job(options, unreadable);
    tracer::AnimationCaches caches;
    g_rendering = true;
    for (std::string line;;) {
        g_waiting_for_regions = true;  // Ctrl-C between runs: stop at once
        const bool got = bool(std::getline(std::cin, line));
        g_waiting_for_regions = false;
        if (!got) return kOk;
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        if (auto problem = frame_request(line, job.range, job.output)) {
            std::cout << "error: " << *problem << std::endl;
            continue;
        }
        nlohmann::ordered_json figures;
        const tracer::AnimationEnd end = tracer::render_animation(job, program, figures, caches);
        if (end == tracer::AnimationEnd::Interrupted)
            exit_interrupted("tracer: interrupted; the frame under way was not written (the frames before it are)\n");
        if (end != tracer::AnimationEnd::Done) {  // said on stderr
            std::cout << "error " << job.range.first << " " << job.range.last_made() << std::endl;
            return end == tracer::AnimationEnd::SceneError ? (unreadable ? kIoError : kSceneError) : kIoError;
        }
        std::cout << "done " << job.range.first << " " << job.range.last_made() << std::endl;
    }
}

// --check --frames N: the scene run and checked at every frame (its files read once).
int check_frames(const Options& options) {
    tracer::SceneProgram program(options.scene, scene_input(options).arguments, standard_input_name(options));
    bool unreadable = false;
    const tracer::AnimationJob job = animation_job(options, unreadable);
    tracer::FileCache files;
    const tracer::FrameRange& range = options.frames;
    for (int frame = range.first; frame <= range.last_made(); ++frame) {
        const tracer::FrameTime time = tracer::frame_time(range, frame);
        if (!job.load(program, time, files, false)) {  // errors only: check_only below reports the first
            std::cerr << "tracer: error: frame " << frame << " (clock " << time.clock << ") has errors\n";
            return unreadable ? kIoError : kSceneError;
        }
    }
    // The first frame's report, as a still's (tools/farm reads its image size), then the frames'.
    const int code = check_only(options);
    if (code == kOk && !options.json_diagnostics)
        std::cout << "  frames: ok at each of " << range.frames_made() << " (" << range.first << " to "
                  << range.last_made() << ")\n";
    return code;
}

int check_only(const Options& options) {
    int exit_code = kOk;
    auto loaded = load(options, exit_code);
    if (!loaded) return exit_code;
    if (options.json_diagnostics) return kOk;  // the JSON line said it
    const tracer::SceneDescription& scene = loaded->scene;
    std::cout << scene_name(options) << ": ok (" << tracer::scene_counts(scene) << ")\n";
    const tracer::RenderSettings& render = scene.render;
    std::cout << "  image: " << render.width << " x " << render.height << " pixels, " << render.samples
              << (render.samples == 1 ? " sample" : " samples") << " per pixel, max depth " << render.max_depth
              << (render.encoding == tracer::Encoding::Srgb ? ", 8-bit files sRGB-encoded" : "") << '\n';
    // Each mesh block's facts, where it puts its triangles (the first few; --dump-json has all).
    constexpr size_t kMeshesListed = 20;
    for (size_t block = 0; block < std::min(scene.meshes.size(), kMeshesListed); ++block) {
        const tracer::Mesh& mesh = scene.meshes[block];
        const auto facts = tracer::mesh_facts(*loaded->meshes.files[loaded->meshes.file_of_block[block]], mesh);
        std::cout << "  mesh " << tracer::shape_label(mesh.path, mesh.line) << ": " << facts.triangles << " triangles, "
                  << facts.vertices << " vertices, placed within " << vector_text(facts.lower) << " to "
                  << vector_text(facts.upper) << '\n';
    }
    if (scene.meshes.size() > kMeshesListed)
        std::cout << "  and " << scene.meshes.size() - kMeshesListed << " more mesh blocks (--dump-json lists all)\n";
    // Every other file the render reads, each once (tools/farm keys its kept tiles on them);
    // the standard library's are part of tracer.
    std::set<std::string> listed;
    for (const std::string& path : scene.included_paths)
        if (listed.insert(path).second)
            std::cout << (tracer::is_library_path(path) ? "  built in: " : "  reads: ") << path << '\n';
    for (const tracer::Mesh& mesh : scene.meshes)
        if (listed.insert(mesh.path).second) std::cout << "  reads: " << mesh.path << '\n';
    return kOk;
}

int dump_json(const Options& options) {
    int exit_code = kOk;
    auto loaded = load(options, exit_code);
    if (!loaded) return exit_code;
    tracer::write_scene_json(std::cout, loaded->scene, &loaded->meshes);
    return kOk;
}

// --watch: the render again after each change to a file the scene reads, until Ctrl-C.
int watch(const Options& options) {
    if (auto problem = tracer::check_output_path(options.output)) {
        std::cerr << "tracer: error: " << *problem << '\n';
        return kIoError;
    }
    tracer::WatchSettings settings{options.scene, options.output,           options.threads,
                                   options.quiet, options.json_diagnostics, &g_interrupted};
    g_rendering = true;  // Ctrl-C asks the loop to stop (a render under way writes nothing)
    tracer::start_threads(options.threads);
    return tracer::watch_scene(
        settings,
        [&](const tracer::ReportLoad& report) {
            int exit_code = kOk;
            return load(options, exit_code, report);
        },
        [&](const tracer::SceneDescription& scene) { return output_clash(options, scene); });
}

int run(int argc, char** argv) {
    Options options;
    CLI::App app{"tracer: renders scene files with Whitted ray tracing and Phong shading.", "tracer"};
    add_options(app, options);
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        return kUsageError;
    }

    auto usage_error = [](const std::string& message) {
        std::cerr << "tracer: error: " << message << "\nRun 'tracer --help' for the options.\n";
        return int(kUsageError);
    };
    if (options.reference) {
        std::cout << tracer::reference_markdown();
        return kOk;
    }
    if (options.language_json) {
        std::cout << json_text(tracer::language_json()) << '\n';
        return kOk;
    }
    if (const std::string problem = combination_problem(options); !problem.empty()) return usage_error(problem);
    // Frames, even one (the same image as in the whole run, bit for bit), go through the frame
    // loop; a look at one frame (--check, --dump-json, --watch, --region-list) is a still at its clock.
    const bool one_frame = options.frames.frames_made() == 1;
    if (options.frame_list) return render_frame_list(options);
    if (options.frames.animated() && options.check && !one_frame) return check_frames(options);
    if (options.frames.animated() && !options.check && !options.dump_json && !options.watch && !options.region_list)
        return render_frames(options);
    if (options.frames.animated()) options.output = tracer::frame_path(options.output, options.frames.first);
    if (options.check) return check_only(options);
    if (options.dump_json) return dump_json(options);
    if (options.watch) return watch(options);
    return render_to_file(options);
}

}  // namespace

int main(int argc, char** argv) {
    std::signal(SIGINT, on_interrupt);
    std::signal(SIGTERM, on_interrupt);
    // Whatever escapes (memory exhausted, a thread that could not start) ends with a message
    // and exit code 3, never std::terminate's abort.
    try {
        return run(argc, argv);
    } catch (const std::bad_alloc&) {
        std::cerr << "tracer: error: out of memory (the scene, its meshes or the image need more memory than "
                     "this machine can give)\n";
    } catch (const std::exception& e) {
        std::cerr << "tracer: error: " << e.what() << '\n';
    }
    return kIoError;
}
