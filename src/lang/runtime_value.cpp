#include "lang/internal/runtime_value.h"

#include <algorithm>

namespace tracer {

ListObject::~ListObject() = default;
FunctionObject::~FunctionObject() = default;

RuntimeValue RuntimeValue::vector(std::span<const double> components) {
    RuntimeValue v;
    v.kind = Kind::Vector;
    if (components.size() <= 3) {
        v.size = uint8_t(components.size());
        std::copy(components.begin(), components.end(), v.x);
        return v;
    }
    auto wide = std::make_shared<WideVectorObject>();
    wide->components.assign(components.begin(), components.end());
    v.size = uint8_t(std::min<size_t>(components.size(), 255));
    v.object = std::move(wide);
    return v;
}

RuntimeValue RuntimeValue::string(std::string text) {
    auto object = std::make_shared<StringObject>();
    object->text = std::move(text);
    RuntimeValue v;
    v.kind = Kind::String;
    v.object = std::move(object);
    return v;
}

RuntimeValue RuntimeValue::list(std::vector<RuntimeValue> items) {
    auto object = std::make_shared<ListObject>();
    object->items = std::move(items);
    RuntimeValue v;
    v.kind = Kind::List;
    v.object = std::move(object);
    return v;
}

std::span<const double> RuntimeValue::components() const {
    if (object) return static_cast<const WideVectorObject&>(*object).components;
    return {x, size};
}

std::string runtime_kind(const RuntimeValue& value) {
    switch (value.kind) {
        case RuntimeValue::Kind::Number: return "a number";
        case RuntimeValue::Kind::Vector: return "a vector of " + std::to_string(value.components().size()) + " numbers";
        case RuntimeValue::Kind::Bool: return value.x[0] != 0 ? "the boolean true" : "the boolean false";
        case RuntimeValue::Kind::String: return "a string";
        case RuntimeValue::Kind::List: {
            const size_t n = value.items().size();
            return "a list of " + std::to_string(n) + (n == 1 ? " value" : " values");
        }
        case RuntimeValue::Kind::Block: return "a " + value.block().kind;
        case RuntimeValue::Kind::Function: return "a function";
        case RuntimeValue::Kind::Broken: return "a value with an error";
    }
    return "a value";
}

bool equal_values(const RuntimeValue& a, const RuntimeValue& b) {
    if (a.kind != b.kind) return false;
    switch (a.kind) {
        case RuntimeValue::Kind::Number:
        case RuntimeValue::Kind::Bool: return a.x[0] == b.x[0];
        case RuntimeValue::Kind::Vector: return std::ranges::equal(a.components(), b.components());
        case RuntimeValue::Kind::String: return a.text() == b.text();
        default: return a.object == b.object;
    }
}

}  // namespace tracer
