#include "app/options.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "lang/load_scene.h"
#include "lang/validate.h"

namespace tracer {
namespace {

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

// --adaptive's check: each part of THRESHOLD[:DEPTH[:CELL]] by the render block's own rules.
std::string adaptive_problem(std::string& text) {
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
}

// A CLI11 check of an override by the render block's own table (the scene's rules and messages),
// which leaves the option's text as the value it checked (a transform: CLI11's checks cannot).
CLI::Validator render_key(const char* key) {
    return CLI::Validator([key](std::string& text) { return override_problem(key, text); }, "", key);
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
        ->transform(render_key("adaptive"));
    app.add_option("--max-depth", options.max_depth, "Override the scene's reflection and refraction depth")
        ->transform(render_key("max_depth"));
    app.add_option("--encoding", options.encoding,
                   "Override how 8-bit images hold the colours: linear (round(255 v), the default) or srgb "
                   "(the sRGB curve, and a PNG marked sRGB, as viewers expect)")
        ->transform(render_key("encoding"));
}

// The animation's options (app/frames.h), read further by combination_problem.
void add_frame_options(CLI::App& app, Options& options) {
    app.add_option("--frames", options.frames.count,
                   "Render an animation of N frames, numbered from 0, into -o's numbered names (a run of # in "
                   "the file name: orbit_###.png); the scene is compiled once and its names clock, clock_delta "
                   "and frame_number follow each frame")
        ->type_name("N")
        ->check(CLI::Validator(
            [](const std::string& text) -> std::string {
                const long long count = std::atoll(text.c_str());
                return count >= 1 && count <= kMostFrames
                           ? ""
                           : "an animation has 1 to " + std::to_string(kMostFrames) +
                                 " frames (over 11 hours at 24 a second); this asks for " + text;
            },
            "N"));
    app.add_option("--clock", options.clock_range,
                   "With --frames: the clock at the first and the last frame (default 0:1)")
        ->type_name("FIRST:LAST");
    app.add_flag("--cyclic", options.frames.cyclic,
                 "With --frames: a loop, the frame after the last being the first again (clock = FIRST + "
                 "(LAST - FIRST) * frame / N, so the last frame falls short of LAST)");
    app.add_option("--subset", options.subset,
                   "With --frames: only frames FIRST to LAST (both made), the clock as in the whole animation; "
                   "one frame alone may be written to a name without a number field")
        ->type_name("FIRST[:LAST]");
    app.add_flag("--frame-list", options.frame_list,
                 "With --frames: load the scene once, then render the runs of frames read from standard input, "
                 "one 'FIRST LAST PATTERN' per line, answering 'done FIRST LAST' on standard output (tools/farm's "
                 "workers); a run that fails ends the process, its error on stderr");
    app.add_flag("--resume", options.frames.resume,
                 "With --frames: keep each frame whose file is already there and whole (of the frame's size), "
                 "render the others");
}

}  // namespace

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
    add_frame_options(app, options);
    app.footer(
        "Exit codes: 0 success, 1 scene errors, 2 bad command line, 3 cannot read the scene or write "
        "the image, 130 interrupted.\nExamples:\n  tracer scenes/task2.scn -o out.png\n"
        "  tracer --check scenes/task2.scn");
}

// The first way the frame options cannot go together, read into options.frames (empty: none).
std::string frames_problem(Options& options) {
    FrameRange& frames = options.frames;
    if (!frames.animated()) {
        if (!options.clock_range.empty() || frames.cyclic || !options.subset.empty() || frames.resume ||
            options.frame_list)
            return "--clock, --cyclic, --subset, --resume and --frame-list are for an animation: give its number "
                   "of frames, --frames N";
        return "";
    }
    if (!options.clock_range.empty())
        if (auto problem = read_clock_range(options.clock_range, frames))
            return "--clock " + options.clock_range + ": " + *problem;
    if (!options.subset.empty())
        if (auto problem = read_subset(options.subset, frames)) return "--subset " + options.subset + ": " + *problem;
    if (auto problem = frame_range_problem(frames)) return *problem;
    if (options.frame_list &&
        (!options.output.empty() || !options.subset.empty() || options.check || options.dump_json || options.watch ||
         options.region_list || !options.region.empty() || frames.resume || options.scene == "-"))
        return "--frame-list takes each run of frames and its output from its input lines: it cannot be combined "
               "with -o, --subset, --resume, --check, --dump-json, --watch, --region or --region-list, or a scene "
               "from standard input";
    if (options.frame_list) return "";
    if (frames.frames_made() == 1) return "";
    const std::string many = std::to_string(frames.frames_made()) + " frames";
    if (options.dump_json) return "--dump-json prints the scene at one frame: choose it with --subset F";
    if (options.watch) return "--watch shows one frame: choose it with --subset F";
    if (options.region_list) return "--region-list renders regions of one frame: choose it with --subset F";
    if (!options.check && !options.output.empty() && !has_number_field(options.output))
        return "-o '" + options.output + "' names one file for " + many +
               ": put a number field in its file name, e.g. frame_####.png (#### becomes 0000, 0001, ...)";
    return "";
}

std::string combination_problem(Options& options) {
    if (options.scene.empty()) return "no scene file given";
    if (std::string problem = frames_problem(options); !problem.empty()) return problem;
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
    if (options.output.empty() && !options.region_list && !options.frame_list)
        return "no output image given (-o out.png)";
    return "";
}

std::string override_problem(const std::string& key, std::string& text) {
    return key == "adaptive" ? adaptive_problem(text) : setting_problem("render", key, text);
}

std::string* override_field(Options& options, const std::string& key) {
    // The overrides: each option's name, without its dashes, and its field.
    const std::pair<const char*, std::string Options::*> fields[] = {
        {"accel", &Options::accel},         {"leaf_size", &Options::leaf_size}, {"width", &Options::width},
        {"height", &Options::height},       {"samples", &Options::samples},     {"adaptive", &Options::adaptive},
        {"max_depth", &Options::max_depth}, {"encoding", &Options::encoding},
    };
    for (const auto& [name, field] : fields)
        if (key == name) return &(options.*field);
    return nullptr;
}

void apply_overrides(const Options& options, SceneDescription& scene) {
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
}

tracer::ParameterValues parameter_values(const Options& options) {
    tracer::ParameterValues out;
    for (const std::string& define : options.defines) {
        const size_t equals = define.find('=');
        out.emplace_back(define.substr(0, equals), define.substr(equals + 1));
    }
    return out;
}

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

std::string standard_input_name(const Options& options) {
    return options.stdin_name.empty() ? std::string(tracer::kStandardInputName) : options.stdin_name;
}

std::string scene_name(const Options& options) {
    return options.scene == "-" ? standard_input_name(options) : options.scene;
}

}  // namespace tracer
