#include "lang/internal/checked_fields.h"

#include <map>
#include <stdexcept>

#include "lang/interpreter.h"

namespace tracer {

// Every table's defaults, parsed once (on first use, by whichever thread comes first) and read
// without a lock after that.
const PlainValue& default_of(const KeySpec& key) {
    static const std::map<const KeySpec*, PlainValue> defaults = [] {
        std::map<const KeySpec*, PlainValue> parsed;
        std::vector<const BlockSpec*> specs = all_block_specs();
        specs.insert(specs.end(), pattern_specs().begin(), pattern_specs().end());
        for (const BlockSpec* spec : specs) {
            for (const KeySpec& row : spec->keys) {
                if (row.required()) continue;
                SourceFile file("<default>", std::string(row.default_value));
                Diagnostics ignored;
                PlainValue value;
                if (!evaluate_single_value(file, ignored, value)) std::abort();  // a broken table: a bug
                parsed.emplace(&row, std::move(value));
            }
        }
        return parsed;
    }();
    const auto found = defaults.find(&key);
    if (found == defaults.end())
        throw std::logic_error("the key '" + std::string(key.name) + "' has no default (it is required)");
    return found->second;
}

Fields::Fields(const BlockSpec& spec) : spec_(&spec) {
    if (spec.keys.size() > kMaxKeys)
        throw std::logic_error("the table of '" + std::string(spec.kind) + "' has more keys than Fields holds");
}

const KeySpec& Fields::key(std::string_view name) const {
    const KeySpec* found = spec_->find_key(name);
    if (!found)
        throw std::logic_error("a builder asked for the key '" + std::string(name) + "', which the table of '" +
                               std::string(spec_->kind) + "' does not have");
    return *found;
}

// The fields of a nested block left out: nothing given, every key its default; made once per
// nested table.
static const Fields& default_fields(const BlockSpec& spec) {
    static const std::map<const BlockSpec*, std::unique_ptr<Fields>> made = [] {
        std::map<const BlockSpec*, std::unique_ptr<Fields>> all;
        for (const BlockSpec* nested : all_block_specs()) all.emplace(nested, std::make_unique<Fields>(*nested));
        return all;
    }();
    return *made.at(&spec);
}

const Fields& Fields::child(std::string_view name) const {
    const KeySpec& row = key(name);
    const std::unique_ptr<Fields>& found = children_[index(row)];
    if (!found && row.type == ValueType::Block && row.block && !has(row)) return default_fields(*row.block);
    if (!found)
        throw std::logic_error("'" + std::string(name) + "' of '" + std::string(spec_->kind) +
                               "' is not a nested block, or was not checked");
    return *found;
}

}  // namespace tracer
