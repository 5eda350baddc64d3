// The built-ins' table: every row whole (a name, an arity, a meaning and a body), and each body
// against its definition, called through the table as the interpreter calls it.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "lang/builtins.h"

namespace tracer {
namespace {

Value num(double x) {
    return number_value(x, Span{});
}
Value vec(double x, double y, double z) {
    return vector_value({x, y, z}, Span{});
}

// Calls the built-in `name` through the table with `args`.
Value call(std::string_view name, std::vector<Value> args) {
    const Builtin* builtin = find_builtin(name);
    EXPECT_NE(builtin, nullptr) << name;
    EXPECT_EQ(builtin->arity, args.size()) << name;
    return builtin->body(BuiltinArguments(builtin->name, args), Span{});
}
double number(std::string_view name, std::vector<Value> args) {
    return call(name, std::move(args)).number;
}
std::vector<double> vector(std::string_view name, std::vector<Value> args) {
    return call(name, std::move(args)).components;
}
// The message of the BuiltinError that calling `name` with `args` throws, or "" if none.
std::string error(std::string_view name, std::vector<Value> args) {
    try {
        call(name, std::move(args));
    } catch (const BuiltinError& e) {
        return e.message;
    }
    return "";
}

TEST(Builtins, EveryRowIsWholeAndNamedOnce) {
    std::set<std::string_view> names;
    for (const Builtin& builtin : all_builtins()) {
        EXPECT_TRUE(names.insert(builtin.name).second) << "twice: " << builtin.name;
        EXPECT_FALSE(builtin.meaning.empty()) << builtin.name;
        EXPECT_NE(builtin.body, nullptr) << builtin.name;
        EXPECT_GE(builtin.arity, 1u) << builtin.name;
        EXPECT_EQ(find_builtin(builtin.name), &builtin);
    }
    EXPECT_EQ(find_builtin("sqr"), nullptr);
}

TEST(Builtins, EachBodyAnswersAsItsDefinition) {
    EXPECT_EQ(number("sqrt", {num(16)}), 4);
    EXPECT_DOUBLE_EQ(number("sin", {num(30)}), std::sin(30 * M_PI / 180));
    EXPECT_DOUBLE_EQ(number("cos", {num(60)}), std::cos(60 * M_PI / 180));
    EXPECT_DOUBLE_EQ(number("tan", {num(45)}), std::tan(45 * M_PI / 180));
    EXPECT_EQ(number("abs", {num(-2.5)}), 2.5);
    EXPECT_EQ(vector("abs", {vec(-1, 2, -3)}), (std::vector<double>{1, 2, 3}));
    EXPECT_EQ(number("floor", {num(-1.5)}), -2);
    EXPECT_EQ(number("min", {num(2), num(-3)}), -3);
    EXPECT_EQ(number("max", {num(2), num(-3)}), 2);
    EXPECT_EQ(number("mod", {num(7), num(3)}), 1);
    EXPECT_EQ(number("mod", {num(-1), num(3)}), 2);  // the divisor's sign
    EXPECT_EQ(number("mod", {num(1), num(-3)}), -2);
    EXPECT_EQ(number("length", {vec(3, 4, 0)}), 5);
    EXPECT_EQ(number("length", {vec(0, 0, 0)}), 0);
    EXPECT_EQ(number("length", {vec(3e300, 4e300, 0)}), 5e300);  // no overflow on the way
    EXPECT_EQ(vector("normalize", {vec(0, 0, -2)}), (std::vector<double>{0, 0, -1}));
    EXPECT_EQ(number("dot", {vec(1, 2, 3), vec(4, 5, 6)}), 32);
    EXPECT_EQ(vector("cross", {vec(1, 0, 0), vec(0, 1, 0)}), (std::vector<double>{0, 0, 1}));  // right-handed
    EXPECT_EQ(number("lerp", {num(1), num(3), num(0.25)}), 1.5);
    EXPECT_EQ(vector("lerp", {vec(0, 0, 0), vec(2, 4, 6), num(0.5)}), (std::vector<double>{1, 2, 3}));
}

TEST(Builtins, ArgumentsOutsideTheDomainAreErrorsNamingThem) {
    EXPECT_EQ(error("sqrt", {num(-1)}), "sqrt of a negative number (-1)");
    EXPECT_EQ(error("mod", {num(1), num(0)}), "mod by zero");
    EXPECT_EQ(error("normalize", {vec(0, 0, 0)}), "normalize of the zero vector");
    EXPECT_EQ(error("sin", {vec(1, 2, 3)}), "'sin''s argument must be a number; this is a vector of 3 numbers");
    EXPECT_EQ(error("dot", {num(1), vec(1, 2, 3)}), "'dot''s argument must be a vector of 3 numbers; this is a number");
    EXPECT_EQ(error("sqrt", {num(2)}), "");
}

}  // namespace
}  // namespace tracer
