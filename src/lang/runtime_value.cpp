#include "lang/internal/runtime_value.h"

#include <algorithm>
#include <charconv>
#include <string>

#include "base/portable.h"

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

namespace {

void append_text(const RuntimeValue& value, bool quoted, std::string& out) {
    if (out.size() > kMaxStringBytes) return;
    auto number = [&](double x) {
        char text[32];
        const auto end = shortest_chars(text, text + sizeof text, x == 0 ? 0.0 : x).ptr;  // -0 as 0
        out.append(text, end);
    };
    switch (value.kind) {
        case RuntimeValue::Kind::Number: number(value.x[0]); return;
        case RuntimeValue::Kind::Bool: out += value.x[0] != 0 ? "true" : "false"; return;
        case RuntimeValue::Kind::Vector: {
            const auto components = value.components();
            out += '(';
            for (size_t i = 0; i < components.size(); ++i) {
                if (i > 0) out += ", ";
                number(components[i]);
            }
            out += ')';
            return;
        }
        case RuntimeValue::Kind::String:
            if (quoted) out += '"';
            out += value.text();
            if (quoted) out += '"';
            return;
        case RuntimeValue::Kind::List: {
            out += '[';
            for (size_t i = 0; i < value.items().size() && out.size() <= kMaxStringBytes; ++i) {
                if (i > 0) out += ", ";
                append_text(value.items()[i], true, out);
            }
            out += ']';
            return;
        }
        default: out += runtime_kind(value);
    }
}

}  // namespace

std::string value_text(const RuntimeValue& value) {
    std::string out;
    append_text(value, false, out);
    return out;
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
        case RuntimeValue::Kind::Vector:
            return std::equal(a.components().begin(), a.components().end(), b.components().begin(),
                              b.components().end());
        case RuntimeValue::Kind::String: return a.text() == b.text();
        default: return a.object == b.object;
    }
}

}  // namespace tracer
