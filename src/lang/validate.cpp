// The validator's checks, driven by the block tables (schema.h), and the entry points.
#include "lang/validate.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>

#include <glm/geometric.hpp>

#include "base/input_file.h"
#include "lang/internal/scene_assembly.h"
#include "lang/internal/suggest.h"
#include "lang/internal/validator.h"
#include "lang/interpreter.h"
#include "lang/schema.h"

namespace tracer {
namespace {

namespace fs = std::filesystem;

std::string describe_found(const PlainValue& value) {
    switch (value.kind) {
        case PlainValue::Kind::Number: return "the number " + format_number(value.number);
        case PlainValue::Kind::Vector:
            return "a vector with " + std::to_string(value.components.size()) + " component" +
                   (value.components.size() == 1 ? "" : "s");
        case PlainValue::Kind::String: return "a string";
        case PlainValue::Kind::Identifier: return in_quotes(value.text);
        case PlainValue::Kind::Block: return value.text.empty() ? "a block { ... }" : "a " + value.text + " { ... }";
        case PlainValue::Kind::List: return "a list of " + std::to_string(value.items.size()) + " values";
        case PlainValue::Kind::Broken: return "a value with an error";
    }
    return "a value";
}

}  // namespace

// One block, checked as soon as it is made (the interpreter hands them over one by one, so
// that a big scene is never held whole).
std::optional<Fields> Validator::check(const Block& block) {
    kept_ = false;
    if (diagnostics_.saturated()) return std::nullopt;
    const BlockSpec* spec = block.spec ? block.spec : find_block_spec(block.kind);
    if (!spec) {
        std::vector<std::string_view> kinds;
        for (const BlockSpec* s : all_block_specs())
            if (s->top_level) kinds.push_back(s->kind);
        diagnostics_.error(
            file_, block.kind_span,
            "unknown block " + in_quotes(block.kind) +
                (povray_hint(block.kind).empty() ? did_you_mean(block.kind, kinds) : povray_hint(block.kind)));
        return std::nullopt;
    }
    if (!check_block_header(block, *spec)) return std::nullopt;
    if (spec->kind == "material") return check_material_block(block);
    if (block.broken) return std::nullopt;
    Fields fields(*spec);
    if (!check_body(block.body, *spec, block.kind_span, fields)) return std::nullopt;
    if (block.group && (spec->kind == "camera" || spec->kind == "render")) {
        const std::string& group = block.group->kind;
        diagnostics_.error(
            file_, block.kind_span,
            "a " + block.kind + " block is not placed by a " + group + ": write it outside the " + group);
        return std::nullopt;
    }
    return fields;
}

// `material NAME { ... }`: its name taken (once), then its body.
std::optional<Fields> Validator::check_material_block(const Block& block) {
    kept_ = true;  // its name's span, for "unused" and "defined twice"
    auto [entry, inserted] = named_.try_emplace(block.name);
    if (!inserted) {
        Diagnostic* d = diagnostics_.error(file_, block.name_span, "material '" + block.name + "' is defined twice");
        Diagnostics::note(d, file_, entry->second.name_span, "the first definition is here");
        return std::nullopt;
    }
    entry->second.name_span = block.name_span;
    if (block.broken) return std::nullopt;  // already reported; keep the name so uses of it are not errors too
    Fields fields(*find_block_spec("material"));
    if (!check_body(block.body, *find_block_spec("material"), block.kind_span, fields)) return std::nullopt;
    entry->second.defined = true;
    return fields;
}

bool Validator::check_material_name(const PlainValue& value) {
    auto found = named_.find(value.text);
    if (found != named_.end()) {
        found->second.used = true;
        return true;
    }
    later_uses_.push_back({value.text, value.span});
    kept_ = true;
    return true;
}

void Validator::finish() {
    // Materials used before their block: now defined, or undefined.
    for (const LaterUse& use : later_uses_) {
        auto found = named_.find(use.name);
        if (found != named_.end()) {
            found->second.used = true;
            continue;
        }
        std::vector<std::string_view> names;
        for (const auto& [name, material] : named_) names.push_back(name);
        diagnostics_.error(file_, use.span,
                           "undefined material " + in_quotes(use.name) + did_you_mean(use.name, names));
    }
    if (!options_.fragment && !first_of_kind_.count(find_block_spec("camera")) && !diagnostics_.saturated())
        diagnostics_.report(Severity::Error, Diagnostics::whole_file(file_.scene().path()),
                            "the scene has no camera block; add one, e.g. camera { eye (0, 0, 7) lookat (0, 0, 0) }");
    // With errors around, an unused material is usually a misspelled use: no extra noise.
    if (!options_.fragment && !diagnostics_.has_errors())
        for (const auto& [name, material] : named_)
            if (!material.used && material.defined)
                diagnostics_.warning(file_, material.name_span, "material '" + name + "' is never used");
}

// Names and counts: `material NAME`, no name elsewhere, one camera, at most one render block.
bool Validator::check_block_header(const Block& block, const BlockSpec& spec) {
    if (spec.named && block.name.empty()) {
        diagnostics_.error(file_, block.kind_span,
                           "a " + block.kind + " block needs a name: " + block.kind + " NAME { ... }");
        return false;
    }
    if (!spec.named && !block.name.empty()) {
        diagnostics_.error(file_, block.name_span,
                           "a " + block.kind + " block takes no name; write " + block.kind + " { ... }");
        return false;
    }
    auto [first, inserted] = first_of_kind_.emplace(&spec, block.kind_span);
    kept_ = kept_ || inserted;
    if (!inserted && spec.occurs != Occurs::Any) {
        Diagnostic* d = diagnostics_.error(file_, block.kind_span, "a scene has only one " + block.kind + " block");
        Diagnostics::note(d, file_, first->second, "the first " + block.kind + " block is here");
        return false;
    }
    return true;
}

// Reports a key the block's table does not have, with the closest known key (remembered in
// `suggested`, so that it is not also reported missing).
bool Validator::unknown_key(const Entry& entry, const BlockSpec& spec, std::vector<std::string>& suggested) {
    std::vector<std::string_view> names;
    for (const KeySpec& k : spec.keys) names.push_back(k.name);
    suggested.push_back(closest_match(entry.key, names));
    diagnostics_.error(file_, entry.key_span,
                       "unknown key " + in_quotes(entry.key) + " in " + std::string(spec.kind) +
                           (povray_hint(entry.key).empty() ? did_you_mean(entry.key, names) : povray_hint(entry.key)));
    return false;
}

bool Validator::check_body(const Body& body, const BlockSpec& spec, Span owner, Fields& fields) {
    if (spec.ordered) return check_steps(body, spec, fields);
    bool ok = true;
    std::vector<std::string> suggested;  // keys offered in "did you mean": not reported missing
    for (const Entry& entry : body.entries) {
        if (diagnostics_.saturated()) return false;
        const bool row_of_this_table =
            entry.spec && entry.spec >= spec.keys.data() && entry.spec < spec.keys.data() + spec.keys.size();
        const KeySpec* key = row_of_this_table ? entry.spec : spec.find_key(entry.key);
        if (!key) {
            ok = unknown_key(entry, spec, suggested);
            continue;
        }
        if (key->placement_step) {  // kept in order, as a transform's steps are
            ok = check_step(entry, *key, spec, fields) && ok;
            continue;
        }
        if (fields.has(*key)) {
            Diagnostic* d = diagnostics_.error(file_, entry.key_span, "duplicate key '" + entry.key + "'");
            Diagnostics::note(d, file_, fields.key_span(*key), "'" + entry.key + "' was first set here");
            ok = false;
            continue;
        }
        fields.set(*key, entry.value, entry.key_span);
        ok = check_value(entry.value, *key, fields) && ok;
    }
    for (const KeySpec& key : spec.keys) {
        if (!key.required() || fields.has(key)) continue;  // nested blocks left out: their defaults
        bool misspelled = std::find(suggested.begin(), suggested.end(), key.name) != suggested.end();
        if (!misspelled) {
            diagnostics_.error(file_, owner,
                               std::string(spec.kind) + " is missing the required key '" + std::string(key.name) +
                                   "' (" + std::string(describe(key.type)) + ")");
            ok = false;
        }
    }
    return ok;
}

// An ordered block (transform): every entry is one step, keys may repeat, order is kept.
bool Validator::check_steps(const Body& body, const BlockSpec& spec, Fields& fields) {
    bool ok = true;
    std::vector<std::string> suggested;
    for (const Entry& entry : body.entries) {
        if (diagnostics_.saturated()) return false;
        const KeySpec* key = spec.find_key(entry.key);
        if (!key) {
            ok = unknown_key(entry, spec, suggested);
            continue;
        }
        ok = check_step(entry, *key, spec, fields) && ok;
    }
    return ok;
}

bool Validator::check_step(const Entry& entry, const KeySpec& key, const BlockSpec& spec, Fields& fields) {
    auto step = std::make_unique<Fields>(spec);
    step->set(key, entry.value, entry.key_span);
    const bool ok = check_value(entry.value, key, *step);
    fields.add_step(std::move(step));
    return ok;
}

bool Validator::type_error(const PlainValue& value, const KeySpec& key, const std::string& extra) {
    std::string message = "'" + std::string(key.name) + "' expects " + std::string(describe(key.type)) + ", found " +
                          describe_found(value);
    if (value.kind == PlainValue::Kind::Identifier && names_nan_or_infinity(value.text))
        message += " (NaN and infinity are not allowed)";
    diagnostics_.error(file_, value.span, message + extra);
    return false;
}

bool Validator::check_value(const PlainValue& value, const KeySpec& key, Fields& fields) {
    using Kind = PlainValue::Kind;
    auto check_vector = [&] {
        if (value.components.size() != 3) return type_error(value, key);
        bool ok = true;
        for (size_t i = 0; i < 3; ++i) ok = check_number(value.components[i], value.component_spans[i], key) && ok;
        dvec3 v{value.components[0], value.components[1], value.components[2]};
        if (ok && key.nonzero && normalized(v) == dvec3(0.0)) {
            diagnostics_.error(file_, value.span, "'" + std::string(key.name) + "' must not be the zero vector");
            return false;
        }
        return ok;
    };
    if (value.kind == Kind::Broken) return false;  // reported where it was made
    switch (key.type) {
        case ValueType::Number:
            return value.kind == Kind::Number ? check_number(value.number, value.span, key) : type_error(value, key);
        case ValueType::Integer:
            if (value.kind != Kind::Number || std::floor(value.number) != value.number) return type_error(value, key);
            return check_number(value.number, value.span, key);
        case ValueType::Boolean:
            if (value.kind == Kind::Identifier && (value.text == "true" || value.text == "false")) return true;
            return type_error(value, key,
                              value.kind == Kind::Identifier ? did_you_mean(value.text, {"true", "false"}) : "");
        case ValueType::Vector: return value.kind == Kind::Vector ? check_vector() : type_error(value, key);
        case ValueType::Triple:
            if (value.kind == Kind::Number) return check_number(value.number, value.span, key);
            return value.kind == Kind::Vector ? check_vector() : type_error(value, key);
        case ValueType::Paint:
            if (value.kind == Kind::Number) return check_number(value.number, value.span, key);
            if (value.kind == Kind::Vector) return check_vector();
            if (value.kind == Kind::Block && find_pattern_spec(value.text)) return check_pattern(value, key, fields);
            return type_error(value, key,
                              value.kind == Kind::Block && value.text.empty()
                                  ? "; a pattern is written with its kind: checker { ... }"
                                  : "");
        case ValueType::ColorMap: return check_color_map(value, key);
        case ValueType::Path:
            if (value.kind != Kind::String) return type_error(value, key);
            if (value.text.empty()) {
                diagnostics_.error(file_, value.span, "'" + std::string(key.name) + "' must not be empty");
                return false;
            }
            return true;
        case ValueType::MaterialRef:
            if (value.kind == Kind::Identifier) return check_material_name(value);
            if (value.kind == Kind::Block) {
                auto child = std::make_unique<Fields>(*find_block_spec("material"));
                bool ok = check_body(*value.body, *find_block_spec("material"), value.span, *child);
                fields.set_child(key, std::move(child));
                return ok;
            }
            return type_error(value, key);
        case ValueType::Choice: {
            if (value.kind == Kind::Identifier &&
                std::find(key.choices.begin(), key.choices.end(), value.text) != key.choices.end())
                return true;
            std::string allowed;
            for (std::string_view choice : key.choices) allowed += (allowed.empty() ? "" : ", ") + std::string(choice);
            std::string hint = value.kind == Kind::Identifier ? did_you_mean(value.text, key.choices) : "";
            diagnostics_.error(file_, value.span,
                               "'" + std::string(key.name) + "' must be one of " + allowed + ", found " +
                                   describe_found(value) + hint);
            return false;
        }
        case ValueType::Block: {
            if (value.kind != Kind::Block) return type_error(value, key);
            auto child = std::make_unique<Fields>(*key.block);
            bool ok = check_body(*value.body, *key.block, value.span, *child);
            fields.set_child(key, std::move(child));
            return ok;
        }
    }
    return false;
}

// Why a value of `key` beyond +-1e30 is refused: the reason for its kind of value (a length's
// is the renderer's float boxes; a colour, an exponent, an angle or an index has its own).
static std::string beyond_range_reason(std::string_view key) {
    for (std::string_view colour : {"ka", "kd", "ks", "km", "kt", "color", "background"})
        if (key == colour)
            return "a colour or weight beyond 1e30 shows nothing more than 1e30 does: every pixel it lights is "
                   "already white, and sums of such colours overflow";
    if (key == "n") return "a Phong exponent of 1e30 already makes the highlight a point";
    if (key == "angle")
        return "only an angle's remainder after whole turns counts, and beyond 1e16 degrees a double "
               "keeps no fraction of a turn";
    if (key == "ior") return "an index of refraction of 1e30 already bends every ray along the normal";
    return "the renderer keeps bounding boxes in float and squares and cubes lengths";
}

// A pattern as a colour: its body against its own table, no deeper than kMostPatternNesting.
bool Validator::check_pattern(const PlainValue& value, const KeySpec& key, Fields& fields) {
    const BlockSpec& spec = *find_pattern_spec(value.text);
    if (pattern_depth_ >= kMostPatternNesting) {
        diagnostics_.error(file_, value.span,
                           "patterns are nested more than " + std::to_string(kMostPatternNesting) +
                               " deep here (a pattern's colours hold patterns that hold patterns ...)");
        return false;
    }
    ++pattern_depth_;
    auto child = std::make_unique<Fields>(spec);
    const bool ok = check_body(*value.body, spec, value.span, *child);
    --pattern_depth_;
    fields.set_child(key, std::move(child));
    return ok;
}

// A colour map: stops [value, colour], values in 0..1 and in order, colours >= 0; not empty.
bool Validator::check_color_map(const PlainValue& value, const KeySpec& key) {
    const std::string name(key.name);
    if (value.kind != PlainValue::Kind::List) return type_error(value, key, "; as in [[0, (1, 0, 0)], [1, 1]]");
    if (value.items.empty()) {
        diagnostics_.error(file_, value.span, "'" + name + "' needs at least one stop [value, colour]");
        return false;
    }
    if (value.items.size() > kMostColorStops) {
        diagnostics_.error(file_, value.span,
                           "'" + name + "' holds at most " + std::to_string(kMostColorStops) + " stops; this has " +
                               std::to_string(value.items.size()));
        return false;
    }
    double previous = 0;
    for (size_t i = 0; i < value.items.size(); ++i) {
        const PlainValue& stop = value.items[i];
        const std::string which = "stop " + std::to_string(i) + " of '" + name + "'";
        auto is_colour = [](const PlainValue& c) {
            return c.kind == PlainValue::Kind::Number ||
                   (c.kind == PlainValue::Kind::Vector && c.components.size() == 3);
        };
        if (stop.kind != PlainValue::Kind::List || stop.items.size() != 2 ||
            stop.items[0].kind != PlainValue::Kind::Number || !is_colour(stop.items[1])) {
            const bool pair = stop.kind == PlainValue::Kind::List && stop.items.size() == 2;
            const std::string found = !pair ? describe_found(stop)
                                      : stop.items[0].kind != PlainValue::Kind::Number
                                          ? "a value that is " + describe_found(stop.items[0])
                                          : "a colour that is " + describe_found(stop.items[1]);
            diagnostics_.error(
                file_, value.span,
                which + " must be [value, colour] (a number, then a number or (r, g, b)), found " + found);
            return false;
        }
        const double at = stop.items[0].number;
        const PlainValue& colour = stop.items[1];
        const std::vector<double> channels =
            colour.kind == PlainValue::Kind::Number ? std::vector<double>{colour.number} : colour.components;
        const bool colour_ok = std::all_of(channels.begin(), channels.end(), [](double c) {
            return std::isfinite(c) && c >= 0 && c <= kLargestMagnitude;
        });
        if (!(at >= 0 && at <= 1) || !colour_ok) {
            diagnostics_.error(file_, value.span,
                               which + (colour_ok ? ": its value must be within 0..1, found " + format_number(at)
                                                  : ": its colour must be finite, 0 to 1e30 in each channel"));
            return false;
        }
        if (i > 0 && at < previous) {
            diagnostics_.error(file_, value.span,
                               which + " is at " + format_number(at) + ", below the stop before it (" +
                                   format_number(previous) + "): stops go in order of value");
            return false;
        }
        previous = at;
    }
    return true;
}

bool Validator::check_number(double number, Span span, const KeySpec& key) {
    // A key whose own range lies within +-1e30 (an angle of view, a depth, a threshold) is told
    // that range; the +-1e30 rule, and its reason, are for the others.
    const bool own_range = std::abs(key.min) <= kLargestMagnitude && std::abs(key.max) <= kLargestMagnitude;
    if (std::abs(number) > kLargestMagnitude && !own_range) {
        diagnostics_.error(file_, span,
                           "'" + std::string(key.name) + "' must lie between -1e30 and 1e30 (" +
                               beyond_range_reason(key.name) + "), found " + format_number(number));
        return false;
    }
    if (key.mirror_size && std::abs(number) < kSmallestSize) {
        diagnostics_.error(file_, span,
                           "'" + std::string(key.name) + "' " +
                               (number == 0 ? std::string("must not be 0 (a negative factor mirrors)")
                                            : "must be at least 1e-30 in size (the smallest size the renderer is "
                                              "tested with)") +
                               ", found " + format_number(number));
        return false;
    }
    bool below = key.min_open ? number <= key.min : number < key.min;
    bool above = key.max_open ? number >= key.max : number > key.max;
    if (!below && !above)
        return (!key.perfect_square || check_perfect_square(number, span, key)) &&
               (!key.power_of_two || check_power_of_two(number, span, key));
    std::string name = "'" + std::string(key.name) + "'";
    std::string rule;
    if (std::isinf(key.max))
        rule = key.min == 0 && !key.min_open
                   ? "must not be negative"
                   : std::string("must be ") + (key.min_open ? "greater than " : "at least ") + format_number(key.min);
    else if (key.min_open || key.max_open)
        rule = "must be greater than " + format_number(key.min) + " and less than " + format_number(key.max);
    else
        rule = "must be between " + format_number(key.min) + " and " + format_number(key.max);
    if (key.min == kSmallestSize)  // a size: not positive, or too small to square
        rule = number <= 0 ? "must be greater than 0"
                           : "must be at least 1e-30 (the smallest size the renderer is tested with)";
    if (above && (key.name == "km" || key.name == "kt"))  // weights of the rays a surface passes on
        rule +=
            " (a surface passes on at most the light that reaches it; weights above 1 multiply along "
            "a ray without bound)";
    diagnostics_.error(file_, span, name + " " + rule + ", found " + format_number(number));
    return false;
}

// A whole number that must be N * N (checked with the key's other rules, so that it is
// reported even when another key of the block is wrong).
bool Validator::check_perfect_square(double number, Span span, const KeySpec& key) {
    const int count = int(number);
    const int root = int(std::lround(std::sqrt(double(count))));
    if (root * root == count) return true;
    const int lower = int(std::floor(std::sqrt(double(count))));
    diagnostics_.error(file_, span,
                       "'" + std::string(key.name) + "' must be a perfect square (N x N stratified samples); try " +
                           std::to_string(lower * lower) + " or " + std::to_string((lower + 1) * (lower + 1)));
    return false;
}

// A number that must be 2^k, k whole (within the key's range, checked before).
bool Validator::check_power_of_two(double number, Span span, const KeySpec& key) {
    int exponent = 0;
    if (std::frexp(number, &exponent) == 0.5) return true;
    const double lower = std::ldexp(1.0, exponent - 1);
    diagnostics_.error(file_, span,
                       "'" + std::string(key.name) + "' must be a power of two (..., 0.5, 1, 2, 4, ...); try " +
                           format_number(lower) + " or " + format_number(2 * lower));
    return false;
}

std::string setting_problem(std::string_view block, std::string_view key, std::string& text) {
    const BlockSpec* spec = find_block_spec(block);
    const KeySpec* key_spec = spec ? spec->find_key(key) : nullptr;
    if (!key_spec) return "no key '" + std::string(key) + "' in " + std::string(block);  // a caller's bug
    Sources sources(std::make_unique<SourceFile>("<command line>", text));
    Diagnostics diagnostics;
    PlainValue value;
    if (evaluate_single_value(sources.scene(), diagnostics, value))
        Validator(sources, diagnostics, {true}).check_setting(value, *key_spec, *spec);
    else if (diagnostics.all().empty())  // more than one value
        return "'" + std::string(key) + "' expects " + std::string(describe(key_spec->type)) + ", found " +
               in_quotes(text);
    if (!diagnostics.all().empty()) return diagnostics.all().front().message;
    if (value.kind == PlainValue::Kind::Number) {  // the value checked, exactly: 4*4 is 16
        char exact[40];
        std::snprintf(exact, sizeof exact, "%.17g", value.number);
        text = exact;
    }
    return "";
}

// The validator checks each block, and the assembly builds what it accepted.
struct SceneBuilder::State {
    State(const Sources& sources, Diagnostics& diagnostics, const ValidateOptions& chosen)
        : options(chosen),
          validator(sources, diagnostics, chosen),
          assembly(sources, diagnostics, [this](const Group& group, Fields& fields) {
              return validator.check_body(group.placement, group_spec(), group.keyword, fields);
          }) {}
    ValidateOptions options;
    Validator validator;
    SceneAssembly assembly;
};

SceneBuilder::SceneBuilder(const Sources& sources, Diagnostics& diagnostics, const ValidateOptions& options)
    : state_(std::make_unique<State>(sources, diagnostics, options)) {}
SceneBuilder::~SceneBuilder() = default;

bool SceneBuilder::add(const Block& block) {
    State& state = *state_;
    state.assembly.kept = false;
    if (std::optional<Fields> fields = state.validator.check(block)) build_block(state.assembly, block, *fields);
    return state.validator.kept() || state.assembly.kept;
}

std::optional<SceneDescription> SceneBuilder::finish(
    const std::vector<std::pair<std::string, PlainValue>>& parameters) {
    State& state = *state_;
    state.validator.finish();
    resolve_later_materials(state.assembly);
    place_later_materials(state.assembly);
    const Diagnostics& diagnostics = state.assembly.diagnostics;
    if (!state.options.fragment && !diagnostics.has_errors()) warn_about_the_picture(state.assembly);
    if (diagnostics.has_errors()) return std::nullopt;
    set_parameters(state.assembly, parameters);
    return std::move(state.assembly.scene);
}

}  // namespace tracer
