#include "lang/evaluated_scene.h"

#include "base/diagnostics.h"

namespace tracer {

std::string kind_of(const Value& value) {
    switch (value.kind) {
        case Value::Kind::Number: return "a number";
        case Value::Kind::Vector: return "a vector of " + std::to_string(value.components.size()) + " numbers";
        case Value::Kind::String: return "a string";
        case Value::Kind::Identifier: return "the word " + in_quotes(value.text);
        case Value::Kind::Block: return "a block";
    }
    return "a value";
}

}  // namespace tracer
