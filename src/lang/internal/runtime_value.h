// A value while a scene program runs: a number, a vector, a boolean, a string, a list, a block
// (a material or a transform written as a value) or a function. Small and cheap to copy: numbers,
// booleans and vectors of up to 3 components hold no heap memory; the rest share immutable
// objects. Spans are not kept here: the code that made a value knows where it was written.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace tracer {

struct Body;
struct FunctionCode;
struct RuntimeValue;

// What the heap-held kinds point to; never changed once made.
struct ValObject {
    virtual ~ValObject() = default;
};
struct StringObject final : ValObject {
    std::string text;
};
struct ListObject final : ValObject {
    std::vector<RuntimeValue> items;
    ~ListObject() override;  // in runtime_value.cpp, where RuntimeValue is complete
};
struct WideVectorObject final : ValObject {  // a vector of more than 3 components
    std::vector<double> components;
};
struct BlockObject final : ValObject {  // material { ... } or transform { ... }, evaluated
    std::string kind;
    std::shared_ptr<Body> body;
};
struct FunctionObject final : ValObject {
    std::shared_ptr<const FunctionCode> code;
    std::vector<RuntimeValue> captures;  // the values of the outer names its body uses, taken when defined
    ~FunctionObject() override;          // in runtime_value.cpp, where RuntimeValue is complete
};

struct RuntimeValue {
    enum class Kind : uint8_t { Number, Vector, Bool, String, List, Block, Function, Broken };
    Kind kind = Kind::Number;
    uint8_t size = 0;         // Vector: its number of components
    double x[3] = {0, 0, 0};  // Number: x[0]; Bool: x[0] is 1 or 0; Vector of up to 3: its components
    std::shared_ptr<const ValObject> object;

    static RuntimeValue number(double value) {
        RuntimeValue v;
        v.x[0] = value;
        return v;
    }
    static RuntimeValue boolean(bool value) {
        RuntimeValue v;
        v.kind = Kind::Bool;
        v.x[0] = value ? 1 : 0;
        return v;
    }
    static RuntimeValue vector3(double a, double b, double c) {
        RuntimeValue v;
        v.kind = Kind::Vector;
        v.size = 3;
        v.x[0] = a, v.x[1] = b, v.x[2] = c;
        return v;
    }
    // A vector of any number of components.
    static RuntimeValue vector(std::span<const double> components);
    static RuntimeValue string(std::string text);
    static RuntimeValue list(std::vector<RuntimeValue> items);
    // A name whose definition had an error (reported): using it is an error already reported.
    static RuntimeValue broken() {
        RuntimeValue v;
        v.kind = Kind::Broken;
        return v;
    }

    bool is_number() const { return kind == Kind::Number; }
    bool is_vector() const { return kind == Kind::Vector; }
    std::span<const double> components() const;
    const std::string& text() const { return static_cast<const StringObject&>(*object).text; }
    const std::vector<RuntimeValue>& items() const { return static_cast<const ListObject&>(*object).items; }
    const BlockObject& block() const { return static_cast<const BlockObject&>(*object); }
    const FunctionObject& function() const { return static_cast<const FunctionObject&>(*object); }
};

// What a value is, for messages: "a number", "a vector of 3 numbers", "a list of 4 values".
std::string runtime_kind(const RuntimeValue& value);
// The longest string a scene may make (joined or from str): longer is an error, not a memory
// blow-up from a loop that doubles one.
constexpr size_t kMaxStringBytes = 1'000'000;

// A value as `str` and `print` write it: numbers in the shortest form that reads back exactly
// (0.1, 1e-30, 3), vectors (1, 2, 3), lists [1, "a"], strings as they are (quoted inside a
// list), booleans true and false, other kinds as their kind ("a material"). Stops once it is
// longer than kMaxStringBytes (the caller then refuses it).
std::string value_text(const RuntimeValue& value);

// True if the two values are equal: the same kind and equal numbers, components or texts (lists,
// blocks and functions: the same one; the language does not compare them).
bool equal_values(const RuntimeValue& a, const RuntimeValue& b);

}  // namespace tracer
