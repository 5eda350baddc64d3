#include "lang/internal/evaluated_scene.h"

#include "base/diagnostics.h"

namespace tracer {

std::string plain_kind(const PlainValue& value) {
    switch (value.kind) {
        case PlainValue::Kind::Number: return "a number";
        case PlainValue::Kind::Vector: return "a vector of " + std::to_string(value.components.size()) + " numbers";
        case PlainValue::Kind::String: return "a string";
        case PlainValue::Kind::Identifier: return "the word " + in_quotes(value.text);
        case PlainValue::Kind::Block: return "a block";
        case PlainValue::Kind::List: return "a list of " + std::to_string(value.items.size()) + " values";
        case PlainValue::Kind::Broken: return "a value with an error";
    }
    return "a value";
}

}  // namespace tracer
