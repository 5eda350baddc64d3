// The checked values of one block, as the builders read them: each key's value as written, or
// else its default from the block's table (schema.h). A key the table does not have is a bug
// in a builder: asking for one throws std::logic_error naming the key and the block, instead of
// reading through a null pointer.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "lang/evaluated_scene.h"
#include "lang/schema.h"
#include "scene/scene.h"

namespace tracer {

// A key's default, parsed once from the scene syntax written in its table row.
const Value& default_of(const KeySpec& key);

class Fields {
public:
    explicit Fields(const BlockSpec& spec) : spec_(&spec) {}

    void set(const KeySpec& key, const Value& value, Span key_span) { given_[key.name] = {&value, key_span}; }
    void set_child(const KeySpec& key, std::unique_ptr<Fields> child) { children_[key.name] = std::move(child); }
    bool has(std::string_view name) const { return given_.count(key(name).name) > 0; }
    Span key_span(std::string_view name) const { return given_.at(name).key_span; }
    Span value_span(std::string_view name) const { return has(name) ? given_.at(name).value->span : Span{}; }

    // The value written for `name`, or the table's default.
    const Value& get(std::string_view name) const {
        auto found = given_.find(name);
        return found != given_.end() ? *found->second.value : default_of(key(name));
    }
    double number(std::string_view name) const { return get(name).number; }
    int integer(std::string_view name) const { return int(get(name).number); }
    bool boolean(std::string_view name) const { return get(name).text == "true"; }
    std::string text(std::string_view name) const { return get(name).text; }
    dvec3 triple(std::string_view name) const {
        const Value& value = get(name);
        if (value.kind == Value::Kind::Number) return dvec3(value.number);
        return {value.components[0], value.components[1], value.components[2]};
    }
    // The checked fields of a nested block (written, or the table's default).
    const Fields& child(std::string_view name) const;
    // An ordered block's steps (transform), each with its one key, in the order written.
    void add_step(std::unique_ptr<Fields> step) { steps_.push_back(std::move(step)); }
    const std::vector<std::unique_ptr<Fields>>& steps() const { return steps_; }

private:
    // The table's row for `name`; throws std::logic_error, naming both, if the block has none.
    const KeySpec& key(std::string_view name) const;

    struct Given {
        const Value* value;
        Span key_span;
    };
    const BlockSpec* spec_;
    std::map<std::string_view, Given> given_;
    std::map<std::string_view, std::unique_ptr<Fields>> children_;
    std::vector<std::unique_ptr<Fields>> steps_;
};

}  // namespace tracer
