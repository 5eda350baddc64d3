#include "lang/val.h"

#include <algorithm>

namespace tracer {

ListObject::~ListObject() = default;
FunctionObject::~FunctionObject() = default;

Val Val::vector(std::span<const double> components) {
    Val v;
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

Val Val::string(std::string text) {
    auto object = std::make_shared<StringObject>();
    object->text = std::move(text);
    Val v;
    v.kind = Kind::String;
    v.object = std::move(object);
    return v;
}

Val Val::list(std::vector<Val> items) {
    auto object = std::make_shared<ListObject>();
    object->items = std::move(items);
    Val v;
    v.kind = Kind::List;
    v.object = std::move(object);
    return v;
}

std::span<const double> Val::components() const {
    if (object) return static_cast<const WideVectorObject&>(*object).components;
    return {x, size};
}

std::string kind_of(const Val& value) {
    switch (value.kind) {
        case Val::Kind::Number: return "a number";
        case Val::Kind::Vector: return "a vector of " + std::to_string(value.components().size()) + " numbers";
        case Val::Kind::Bool: return value.x[0] != 0 ? "the boolean true" : "the boolean false";
        case Val::Kind::String: return "a string";
        case Val::Kind::List: {
            const size_t n = value.items().size();
            return "a list of " + std::to_string(n) + (n == 1 ? " value" : " values");
        }
        case Val::Kind::Block: return "a " + value.block().kind;
        case Val::Kind::Function: return "a function";
        case Val::Kind::Broken: return "a value with an error";
    }
    return "a value";
}

bool equal_values(const Val& a, const Val& b) {
    if (a.kind != b.kind) return false;
    switch (a.kind) {
        case Val::Kind::Number:
        case Val::Kind::Bool: return a.x[0] == b.x[0];
        case Val::Kind::Vector: return std::ranges::equal(a.components(), b.components());
        case Val::Kind::String: return a.text() == b.text();
        default: return a.object == b.object;
    }
}

}  // namespace tracer
