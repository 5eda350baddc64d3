// The command line's options: what tracer was asked to do, read and checked by CLI11, and the
// overrides it applies to the scene's render block.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/frames.h"
#include "lang/interpreter.h"
#include "scene/scene.h"

namespace tracer {

// Every option and flag, as given.
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
    // Animation: --frames, --clock, --cyclic, --subset, --resume (app/frames.h), as read.
    FrameRange frames;
    std::string clock_range;
    std::string subset;
    bool frame_list = false;  // --frame-list: runs of frames read from stdin (tools/farm's workers)
};

// Every option and flag of the command line, bound to `options`.
void add_options(CLI::App& app, Options& options);
// The first way the options given cannot go together (empty: none); reads the frame options
// into options.frames.
std::string combination_problem(Options& options);
// Why `text` for the render override `key` (a --KEY of the command line without its dashes,
// underscores for dashes: width, max_depth, adaptive, ...) is refused, or empty: the scene's own
// rules; the text is left as the value checked.
std::string override_problem(const std::string& key, std::string& text);
// The field of `options` that holds the render override `key`, or nullptr if there is none.
std::string* override_field(Options& options, const std::string& key);
// The command line's overrides of the scene's render block, applied to `scene`.
void apply_overrides(const Options& options, SceneDescription& scene);

// The -D NAME=VALUE definitions (checked to have a '=' when parsed).
ParameterValues parameter_values(const Options& options);
// The folders includes are looked for in: -I's in order, then TRACER_PATH's (':' between them).
std::vector<std::string> include_folders(const Options& options);
// The name a scene read from standard input goes by (--stdin-name, else <stdin>).
std::string standard_input_name(const Options& options);
// The scene's name in messages.
std::string scene_name(const Options& options);

}  // namespace tracer
