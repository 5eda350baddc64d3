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
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <new>

#include "app/diagnostics_json.h"
#include "app/load_files.h"
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

// --adaptive's THRESHOLD[:DEPTH[:CELL]] split at its colons (empty parts kept, to be refused).
std::vector<std::string> adaptive_parts(const std::string& text) {
    std::vector<std::string> parts{""};
    for (char c : text)
        if (c == ':')
            parts.emplace_back();
        else
            parts.back().push_back(c);
    return parts;
}

struct Options {
    std::string scene;
    std::string output;
    int threads = 0;
    bool quiet = false;
    bool check = false;
    bool dump_json = false;
    bool reference = false;
    // Overrides of the scene's render block, as written (empty: the scene's), checked by the
    // scene's own rules (setting_problem).
    std::string accel;
    std::string leaf_size;
    std::string width;
    std::string height;
    std::string samples;
    std::string adaptive;  // THRESHOLD[:DEPTH[:CELL]]
    std::string max_depth;
    std::string encoding;                   // --encoding linear|srgb
    std::vector<std::string> defines;       // -D NAME=VALUE
    std::vector<std::string> include_dirs;  // -I DIR
    std::vector<int> region;                // --region X0 Y0 W H (empty: the whole frame)
    bool region_list = false;               // --region-list: regions read from stdin
    bool stats = false;
    std::string stats_json;
    bool json_diagnostics = false;  // --diagnostics json: one line of JSON per load on stdout
    std::string stdin_name;         // the name of a scene read from standard input
    bool language_json = false;
    bool watch = false;
};

// The -D NAME=VALUE definitions (checked to have a '=' when parsed).
tracer::ParameterValues parameter_values(const Options& options) {
    tracer::ParameterValues out;
    for (const std::string& define : options.defines) {
        const size_t equals = define.find('=');
        out.emplace_back(define.substr(0, equals), define.substr(equals + 1));
    }
    return out;
}

// The folders includes are looked for in: -I's in order, then TRACER_PATH's (':' between them).
std::vector<std::string> include_folders(const Options& options) {
    std::vector<std::string> folders = options.include_dirs;
    const char* path = std::getenv("TRACER_PATH");
    for (std::string_view rest = path ? path : ""; !rest.empty();) {
        const size_t colon = rest.find(':');
        if (const std::string_view folder = rest.substr(0, colon); !folder.empty()) folders.emplace_back(folder);
        rest = colon == std::string_view::npos ? std::string_view{} : rest.substr(colon + 1);
    }
    return folders;
}

// The name a scene read from standard input goes by (--stdin-name, else <stdin>).
std::string standard_input_name(const Options& options) {
    return options.stdin_name.empty() ? std::string(tracer::kStandardInputName) : options.stdin_name;
}

// The scene's name in messages.
std::string scene_name(const Options& options) {
    return options.scene == "-" ? standard_input_name(options) : options.scene;
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
    tracer::SceneInput input{
        options.scene, standard_input_name(options), {parameter_values(options), include_folders(options)}};
    auto loaded = tracer::load_scene_with_meshes(
        input,
        [&](tracer::SceneDescription& scene) {
            tracer::RenderSettings& render = scene.render;
            if (!options.accel.empty()) tracer::accelerator_from_name(options.accel, render.accel);
            if (!options.encoding.empty()) tracer::encoding_from_name(options.encoding, render.encoding);
            // Each option's text is the number its check read (setting_problem wrote it back).
            auto number = [](const std::string& text) { return std::strtod(text.c_str(), nullptr); };
            auto whole = [&](const std::string& text, int scene_value) {
                return text.empty() ? scene_value : int(number(text));
            };
            render.leaf_size = whole(options.leaf_size, render.leaf_size);
            render.samples = whole(options.samples, render.samples);
            if (!options.adaptive.empty()) {
                // The command line's choice of sampling wins over the scene's samples, unless it
                // gives --samples too (then render_settings_problem names the clash).
                const std::vector<std::string> parts = adaptive_parts(options.adaptive);  // checked
                render.antialias = tracer::Antialias::Adaptive;
                render.adaptive_threshold = number(parts[0]);
                if (parts.size() > 1) render.adaptive_depth = int(number(parts[1]));
                if (parts.size() > 2) render.adaptive_cell = number(parts[2]);
                if (options.samples.empty()) render.samples = 1;
            }
            render.max_depth = whole(options.max_depth, render.max_depth);
            // One of width and height alone keeps the scene's aspect ratio (as tools/crosscheck).
            const double aspect = double(render.width) / double(render.height);
            render.width = whole(options.width, render.width);
            render.height = whole(options.height, render.height);
            if (!options.width.empty() && options.height.empty())
                render.height = std::max(1, int(std::lround(render.width / aspect)));
            if (!options.height.empty() && options.width.empty())
                render.width = std::max(1, int(std::lround(render.height * aspect)));
        },
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
    if (!options.stats_json.empty())
        if (auto problem = tracer::output_path_problem(options.stats_json)) {
            std::cerr << "tracer: error: cannot write '" << options.stats_json << "': " << *problem << '\n';
            return kIoError;
        }
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
    const tracer::World world(loaded->scene, loaded->meshes, options.threads, tracer::World::ReleaseFlatShapes{});
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
    if (!options.stats_json.empty())
        if (auto problem = tracer::write_file_atomically(options.stats_json, json_text(figures) + '\n')) {
            std::cerr << "tracer: error: cannot write '" << options.stats_json << "': " << *problem << '\n';
            return kIoError;
        }
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
        const auto facts = tracer::mesh_facts(loaded->meshes.files[loaded->meshes.file_of_block[block]], mesh);
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

// A CLI11 check of an override by the render block's own table (the scene's rules and messages),
// which leaves the option's text as the value it checked (a transform: CLI11's checks cannot).
CLI::Validator render_key(const char* key) {
    return CLI::Validator([key](std::string& text) { return tracer::setting_problem("render", key, text); }, "", key);
}

// The options that override the scene's render block, each checked by the block's own table.
void add_render_overrides(CLI::App& app, Options& options) {
    app.add_option("--accel", options.accel, "Override the scene's mesh accelerator (none, box, median, sah)")
        ->transform(render_key("accel"));
    app.add_option("--leaf-size", options.leaf_size, "Override the scene's BVH leaf size")
        ->transform(render_key("leaf_size"));
    app.add_option("--width", options.width,
                   "Override the scene's image width (alone: the height follows the aspect ratio)")
        ->transform(render_key("width"));
    app.add_option("--height", options.height,
                   "Override the scene's image height (alone: the width follows the aspect ratio)")
        ->transform(render_key("height"));
    app.add_option("--samples", options.samples, "Override the scene's samples per pixel (N*N: 1, 4, 9, 16, ...)")
        ->transform(render_key("samples"));
    app.add_option("--adaptive", options.adaptive,
                   "Adaptive antialiasing: split cells where their corners differ by THRESHOLD (0..1 per "
                   "channel), down to DEPTH levels below a pixel, from cells CELL pixels wide (defaults: the "
                   "scene's, else 3 and 1); replaces --samples")
        ->type_name("THRESHOLD[:DEPTH[:CELL]]")
        ->transform(CLI::Validator(
            [](std::string& text) {
                std::vector<std::string> parts = adaptive_parts(text);
                if (parts.size() > 3 || std::any_of(parts.begin(), parts.end(), [](auto& p) { return p.empty(); }))
                    return std::string("expected THRESHOLD[:DEPTH[:CELL]], e.g. 0.05:3 or 0.05:3:4");
                const char* keys[] = {"adaptive_threshold", "adaptive_depth", "adaptive_cell"};
                for (size_t i = 0; i < parts.size(); ++i)
                    if (std::string problem = tracer::setting_problem("render", keys[i], parts[i]); !problem.empty())
                        return problem;
                text = parts[0];  // each part as its check read it
                for (size_t i = 1; i < parts.size(); ++i) text += ":" + parts[i];
                return std::string();
            },
            "", "adaptive"));
    app.add_option("--max-depth", options.max_depth, "Override the scene's reflection and refraction depth")
        ->transform(render_key("max_depth"));
    app.add_option("--encoding", options.encoding,
                   "Override how 8-bit images hold the colours: linear (round(255 v), the default) or srgb "
                   "(the sRGB curve, and a PNG marked sRGB, as viewers expect)")
        ->transform(render_key("encoding"));
}

// Every option and flag of the command line, bound to `options`.
void add_options(CLI::App& app, Options& options) {
    app.set_version_flag("--version", std::string("tracer ") + TRACER_VERSION);
    app.add_option("scene", options.scene, "The scene file (.scn), or - for standard input");
    app.add_option("-o,--output", options.output,
                   "The image to write; the format follows the extension (.png, .exr, ...)");
    app.add_option("--threads", options.threads,
                   "Threads that build the BVHs and render the image (default: every core; oneTBB's)")
        ->check(CLI::Range(1, 1024));
    app.add_flag("-q,--quiet", options.quiet, "No progress indicator and no summary line");
    add_render_overrides(app, options);
    app.add_option("-D,--define", options.defines,
                   "Set a parameter of the scene (declared there by 'param NAME = VALUE'): -D radius=0.3, "
                   "-D colour=(1,0,0); repeatable")
        ->check(CLI::Validator(
            [](std::string& text) -> std::string {
                const size_t equals = text.find('=');
                return equals == std::string::npos || equals == 0 ? "expected NAME=VALUE, e.g. -D radius=0.3" : "";
            },
            "NAME=VALUE"))
        ->allow_extra_args(false);
    app.add_option("-I,--include-dir", options.include_dirs,
                   "Look for an included file here when it is not beside the file that includes it; repeatable, "
                   "searched in order, then the folders of TRACER_PATH (separated by ':'). include \"std/...\" "
                   "is the standard library built into tracer")
        ->allow_extra_args(false);
    app.add_option("--region", options.region,
                   "Render only this window of the frame, each pixel as the whole render has it: X0 Y0 W H "
                   "(left, top, width, height in pixels); EXR records it as the data window")
        ->expected(4);
    app.add_flag("--region-list", options.region_list,
                 "Load the scene once, then render the regions read from standard input, one 'X0 Y0 W H OUTPUT' "
                 "per line, answering 'done OUTPUT' or 'error OUTPUT: message' on standard output (tools/farm's "
                 "workers)");
    app.add_flag("--stats", options.stats, "Print BVH and ray statistics on stderr");
    app.add_option("--stats-json", options.stats_json, "Write the statistics as JSON to this file");
    app.add_flag("--check", options.check, "Only check the scene; report every problem found");
    app.add_flag("--dump-json", options.dump_json, "Print the resolved scene description as JSON on stdout");
    app.add_flag("--reference", options.reference, "Print the scene language reference (Markdown) on stdout");
    app.add_flag("--language-json", options.language_json,
                 "Print the language's blocks, keys, statements and built-ins as JSON on stdout (for editors)");
    app.add_option_function<std::string>(
           "--diagnostics", [&options](const std::string& format) { options.json_diagnostics = format == "json"; },
           "How problems in the scene are reported: text on stderr (default), or json: one line of JSON "
           "on stdout per load (with --watch, one per event)")
        ->check(CLI::IsMember({"text", "json"}));
    app.add_option("--stdin-name", options.stdin_name,
                   "With the scene '-': the path messages give it; its relative paths start from that folder "
                   "(editors check unsaved text this way)");
    app.add_flag("--watch", options.watch,
                 "Render, then render again whenever the scene, a file it includes or a mesh changes (a quick "
                 "preview first, then the full image); Ctrl-C stops");
    app.footer(
        "Exit codes: 0 success, 1 scene errors, 2 bad command line, 3 cannot read the scene or write "
        "the image, 130 interrupted.\nExamples:\n  tracer scenes/task2.scn -o out.png\n"
        "  tracer --check scenes/task2.scn");
}

// The first way the options given cannot go together (empty: none).
std::string combination_problem(const Options& options) {
    if (options.scene.empty()) return "no scene file given";
    if (options.check && options.dump_json) return "--check and --dump-json cannot be combined";
    if (options.dump_json && options.json_diagnostics)
        return "--dump-json writes the scene on stdout; it cannot be combined with --diagnostics json";
    if (!options.stdin_name.empty() && options.scene != "-")
        return "--stdin-name names a scene read from standard input; give the scene as '-'";
    if (options.watch && (options.check || options.dump_json || options.scene == "-" || !options.region.empty() ||
                          options.region_list || !options.stats_json.empty()))
        return "--watch renders a scene file to -o again after each change; it cannot be combined with --check, "
               "--dump-json, --region, --region-list, --stats-json or a scene from standard input";
    if ((options.check || options.dump_json) && !options.output.empty())
        return "-o is for rendering; it cannot be combined with --check or --dump-json";
    if ((options.check || options.dump_json) && (!options.region.empty() || options.region_list))
        return "--region and --region-list are for rendering; they cannot be combined with --check or "
               "--dump-json";
    if (options.check || options.dump_json) return "";
    if (options.region_list &&
        (!options.output.empty() || !options.region.empty() || options.stats || !options.stats_json.empty()))
        return "--region-list takes each output from its input lines; it cannot be combined with -o, "
               "--region, --stats or --stats-json";
    if (options.region_list && options.scene == "-")
        return "--region-list reads its regions from standard input, so the scene cannot come from there too ('-'); "
               "give the scene's file";
    if (options.output.empty() && !options.region_list) return "no output image given (-o out.png)";
    return "";
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
