// The checked values of one block, as the builders read them: each key's value as written, or
// else its default from the block's table (schema.h). A key the table does not have is a bug
// in a builder: asking for one throws std::logic_error naming the key and the block, instead of
// reading through a null pointer.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "lang/internal/evaluated_scene.h"
#include "lang/schema.h"
#include "scene/scene.h"

namespace tracer {

// Scales a vector to unit length without overflow or underflow; zero stays zero.
dvec3 normalized(dvec3 v);

// A key's default, parsed once from the scene syntax written in its table row.
const PlainValue& default_of(const KeySpec& key);

class Fields {
public:
    // Most keys one table may have (Fields keeps one slot per key, without allocating).
    static constexpr size_t kMaxKeys = 16;

    explicit Fields(const BlockSpec& spec);

    void set(const KeySpec& key, const PlainValue& value, Span key_span) { given_[index(key)] = {&value, key_span}; }
    void set_child(const KeySpec& key, std::unique_ptr<Fields> child) { children_[index(key)] = std::move(child); }
    bool has(std::string_view name) const { return has(key(name)); }
    bool has(const KeySpec& row) const { return given_[index(row)].value != nullptr; }
    Span key_span(const KeySpec& row) const { return given_[index(row)].key_span; }
    Span key_span(std::string_view name) const { return given_[index(key(name))].key_span; }
    Span value_span(std::string_view name) const { return has(name) ? get(name).span : Span{}; }

    // The value written for `name`, or the table's default.
    const PlainValue& get(std::string_view name) const {
        const KeySpec& row = key(name);
        const PlainValue* given = given_[index(row)].value;
        return given ? *given : default_of(row);
    }
    double number(std::string_view name) const { return get(name).number; }
    int integer(std::string_view name) const { return int(get(name).number); }
    bool boolean(std::string_view name) const { return get(name).text == "true"; }
    std::string text(std::string_view name) const { return get(name).text; }
    dvec3 triple(std::string_view name) const {
        const PlainValue& value = get(name);
        if (value.kind == PlainValue::Kind::Number) return dvec3(value.number);
        return {value.components[0], value.components[1], value.components[2]};
    }
    // The checked fields of a nested block (written, or else the table's default, shared).
    const Fields& child(std::string_view name) const;
    // The steps of an ordered block (transform) or of a placed block (its scale, rotate, translate
    // and transform keys), each with its one key, in the order written.
    void add_step(std::unique_ptr<Fields> step) { steps_.push_back(std::move(step)); }
    const std::vector<std::unique_ptr<Fields>>& steps() const { return steps_; }
    const BlockSpec& spec() const { return *spec_; }

private:
    // The table's row for `name`; throws std::logic_error, naming both, if the block has none.
    const KeySpec& key(std::string_view name) const;
    size_t index(const KeySpec& key) const { return size_t(&key - spec_->keys.data()); }

    struct Given {
        const PlainValue* value = nullptr;
        Span key_span;
    };
    const BlockSpec* spec_;
    std::array<Given, kMaxKeys> given_{};
    std::array<std::unique_ptr<Fields>, kMaxKeys> children_{};
    std::vector<std::unique_ptr<Fields>> steps_;
};

}  // namespace tracer
