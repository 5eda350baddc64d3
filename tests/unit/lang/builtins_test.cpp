// The built-ins' table: every row whole (a name, an arity, a meaning and a body), and each body
// against its definition, called through the table as the interpreter calls it.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "lang/internal/builtins.h"

namespace tracer {
namespace {

RuntimeValue num(double x) {
    return RuntimeValue::number(x);
}
RuntimeValue vec(double x, double y, double z) {
    return RuntimeValue::vector3(x, y, z);
}

// Calls the built-in `name` through the table with `args`.
RuntimeValue call(std::string_view name, std::vector<RuntimeValue> args) {
    const Builtin* builtin = find_builtin(name);
    EXPECT_NE(builtin, nullptr) << name;
    EXPECT_EQ(builtin->arity, args.size()) << name;
    const std::vector<Span> spans(args.size());
    return builtin->body(BuiltinArguments(builtin->name, args, spans, Span{}));
}
double number(std::string_view name, std::vector<RuntimeValue> args) {
    return call(name, std::move(args)).x[0];
}
std::vector<double> vector(std::string_view name, std::vector<RuntimeValue> args) {
    const RuntimeValue result = call(name, std::move(args));  // its components live in it
    const auto c = result.components();
    return {c.begin(), c.end()};
}
// The message of the BuiltinError that calling `name` with `args` throws, or "" if none.
std::string error(std::string_view name, std::vector<RuntimeValue> args) {
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

TEST(Builtins, PowersLogarithmsAndInverseTrigonometryInDegrees) {
    EXPECT_EQ(number("pow", {num(2), num(10)}), 1024);
    EXPECT_EQ(number("pow", {num(-2), num(3)}), -8);
    EXPECT_EQ(number("pow", {num(4), num(0.5)}), 2);
    EXPECT_EQ(number("pow", {num(0), num(0)}), 1);
    EXPECT_DOUBLE_EQ(number("exp", {num(1)}), std::exp(1.0));
    EXPECT_DOUBLE_EQ(number("log", {num(std::exp(2.0))}), 2);
    EXPECT_DOUBLE_EQ(number("asin", {num(0.5)}), 30);
    EXPECT_DOUBLE_EQ(number("acos", {num(0.5)}), 60);
    EXPECT_EQ(number("acos", {num(-1)}), 180);
    EXPECT_DOUBLE_EQ(number("atan", {num(1)}), 45);
    EXPECT_DOUBLE_EQ(number("atan2", {num(1), num(-1)}), 135);
    EXPECT_EQ(number("atan2", {num(0), num(-1)}), 180);
    EXPECT_DOUBLE_EQ(number("atan2", {num(-1), num(0)}), -90);
    // Each inverse undoes its function (in degrees).
    for (double degrees : {-80.0, -30.0, 0.0, 10.0, 89.0}) {
        EXPECT_NEAR(number("asin", {num(number("sin", {num(degrees)}))}), degrees, 1e-12);
        EXPECT_NEAR(number("atan", {num(number("tan", {num(degrees)}))}), degrees, 1e-12);
    }
    const BuiltinConstant* pi = find_constant("pi");
    ASSERT_NE(pi, nullptr);
    EXPECT_EQ(pi->value, M_PI);
}

// random(seed, i) is SplitMix64's finaliser of the two numbers' bits, as grammar/README.md
// states it; these values come from an independent implementation of that statement (Python's
// integers), so any machine or compiler that gives others breaks the promise.
TEST(Builtins, LenCountsAListsValues) {
    EXPECT_EQ(number("len", {RuntimeValue::list({})}), 0);
    EXPECT_EQ(number("len", {RuntimeValue::list({num(1), vec(1, 2, 3), RuntimeValue::list({num(1), num(2)})})}), 3);
    EXPECT_EQ(error("len", {num(3)}), "'len''s argument must be a list; this is a number");
}

TEST(Builtins, RandomIsTheDocumentedSequenceOnEveryMachine) {
    EXPECT_EQ(number("random", {num(0), num(0)}), 0.28176129772258496);
    EXPECT_EQ(number("random", {num(1), num(0)}), 0.5085127456672683);
    EXPECT_EQ(number("random", {num(0), num(1)}), 0.7093767190854734);
    EXPECT_EQ(number("random", {num(42), num(7)}), 0.1300458907839881);
    EXPECT_EQ(number("random", {num(-3.5), num(1e6)}), 0.6155468776928535);
    EXPECT_EQ(number("random", {num(7), num(-0.0)}), number("random", {num(7), num(0)}));  // -0 is 0
    // In [0, 1), and spread like uniform numbers: the mean of 100,000 draws within 0.005 of 1/2,
    // and two seeds' draws uncorrelated (the mean of their products within 0.005 of 1/4).
    double sum = 0, products = 0;
    for (int i = 0; i < 100000; ++i) {
        const double a = number("random", {num(1), num(i)}), b = number("random", {num(2), num(i)});
        ASSERT_GE(a, 0);
        ASSERT_LT(a, 1);
        sum += a;
        products += a * b;
    }
    EXPECT_NEAR(sum / 100000, 0.5, 0.005);
    EXPECT_NEAR(products / 100000, 0.25, 0.005);
}

TEST(Builtins, ArgumentsOutsideTheDomainAreErrorsNamingThem) {
    EXPECT_EQ(error("sqrt", {num(-1)}), "sqrt of a negative number (-1)");
    EXPECT_EQ(error("mod", {num(1), num(0)}), "mod by zero");
    EXPECT_EQ(error("normalize", {vec(0, 0, 0)}), "normalize of the zero vector");
    EXPECT_EQ(error("sin", {vec(1, 2, 3)}), "'sin''s argument must be a number; this is a vector of 3 numbers");
    EXPECT_EQ(error("dot", {num(1), vec(1, 2, 3)}), "'dot''s argument must be a vector of 3 numbers; this is a number");
    EXPECT_EQ(error("pow", {num(-2), num(0.5)}), "pow of a negative number (-2) to a power that is not whole (0.5)");
    EXPECT_EQ(error("pow", {num(0), num(-1)}), "pow of 0 to a negative power (-1)");
    EXPECT_EQ(error("log", {num(0)}), "log of a number not above 0 (0)");
    EXPECT_EQ(error("asin", {num(1.5)}), "asin of a number outside -1..1 (1.5)");
    EXPECT_EQ(error("acos", {num(-2)}), "acos of a number outside -1..1 (-2)");
    EXPECT_EQ(error("atan2", {num(0), num(0)}), "atan2 of (0, 0): the angle of the zero vector");
    EXPECT_EQ(error("sqrt", {num(2)}), "");
}

}  // namespace
}  // namespace tracer
