// The validator: checks each block against its table (schema.h), value by value, and hands
// back its checked fields for the builders (scene_assembly.h); at the end, the checks of the
// whole scene (undefined and unused materials, a missing camera). It builds nothing. Internal to
// lang/.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/diagnostics.h"
#include "base/source.h"
#include "lang/internal/checked_fields.h"
#include "lang/internal/evaluated_scene.h"
#include "lang/schema.h"
#include "lang/validate.h"

namespace tracer {

class Validator {
public:
    Validator(const Sources& sources, Diagnostics& diagnostics, const ValidateOptions& options)
        : file_(sources), diagnostics_(diagnostics), options_(options) {}

    // The checked fields of one block, or nothing if it is refused (reported) or has nothing to
    // build. A material's name is taken even when its body is refused, so that its uses are
    // not errors too.
    std::optional<Fields> check(const Block& block);
    // True if the last check kept a span of its block for later (in a message yet to come).
    bool kept() const { return kept_; }
    // Checks a body against a table, filling `fields`; `owner` is where a missing key is reported.
    bool check_body(const Body& body, const BlockSpec& spec, Span owner, Fields& fields);
    // The whole scene's checks, once every block is in: materials used and never defined (or
    // defined and never used: warnings, when there are no errors), and the camera.
    void finish();
    // Checks one value of `key` as a scene's block would (its type, range and other rules).
    bool check_setting(const PlainValue& value, const KeySpec& key, const BlockSpec& spec) {
        Fields fields(spec);
        fields.set(key, value, value.span);
        return check_value(value, key, fields);
    }

private:
    // The table-driven checks.
    bool check_block_header(const Block& block, const BlockSpec& spec);
    std::optional<Fields> check_material_block(const Block& block);
    bool check_steps(const Body& body, const BlockSpec& spec, Fields& fields);
    // One step of an ordered chain (a transform's, or a placed block's own), checked and kept in order.
    bool check_step(const Entry& entry, const KeySpec& key, const BlockSpec& spec, Fields& fields);
    bool unknown_key(const Entry& entry, const BlockSpec& spec, std::vector<std::string>& suggested);
    bool check_value(const PlainValue& value, const KeySpec& key, Fields& fields);
    bool check_pattern(const PlainValue& value, const KeySpec& key, Fields& fields);
    bool check_color_map(const PlainValue& value, const KeySpec& key);
    bool check_number(double number, Span span, const KeySpec& key);
    bool check_perfect_square(double number, Span span, const KeySpec& key);
    bool check_power_of_two(double number, Span span, const KeySpec& key);
    bool type_error(const PlainValue& value, const KeySpec& key, const std::string& extra = "");
    // A material used by name: marks it used, or keeps the use to be checked at the end (it may
    // be defined further down).
    bool check_material_name(const PlainValue& value);

    const Sources& file_;  // the scene file and those it includes
    Diagnostics& diagnostics_;
    ValidateOptions options_;

    struct NamedMaterial {
        Span name_span;
        bool defined = false;  // its block's body was accepted
        bool used = false;
    };
    std::map<std::string, NamedMaterial, std::less<>> named_;
    struct LaterUse {  // a material used by name before its block
        std::string name;
        Span span;
    };
    std::vector<LaterUse> later_uses_;
    std::map<const BlockSpec*, Span> first_of_kind_;  // each kind's first block, by its table
    int pattern_depth_ = 0;                           // patterns being checked, one inside another
    bool kept_ = false;  // the block being checked had a span of its kept (in the members above)
};

}  // namespace tracer
