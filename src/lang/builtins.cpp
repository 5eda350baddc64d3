#include "lang/internal/builtins.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>

#include "lang/schema.h"
#include "scene/noise.h"

namespace tracer {

double BuiltinArguments::number(size_t i) const {
    const RuntimeValue& value = values_[i];
    if (!value.is_number())
        throw BuiltinError{
            spans_[i], "'" + std::string(function_) + "''s argument must be a number; this is " + runtime_kind(value)};
    return value.x[0];
}

std::span<const double> BuiltinArguments::vector(size_t i) const {
    const RuntimeValue& value = values_[i];
    if (!value.is_vector() || value.size != 3)
        throw BuiltinError{spans_[i], "'" + std::string(function_) +
                                          "''s argument must be a vector of 3 numbers; this is " + runtime_kind(value)};
    return value.components();
}

const std::vector<RuntimeValue>& BuiltinArguments::list(size_t i) const {
    const RuntimeValue& value = values_[i];
    if (value.kind != RuntimeValue::Kind::List)
        throw BuiltinError{
            spans_[i], "'" + std::string(function_) + "''s argument must be a list; this is " + runtime_kind(value)};
    return value.items();
}

namespace {

constexpr double kRadians = std::numbers::pi / 180;

// The length of v, computed without overflow, and v scaled by 1/largest component (zero: 0).
double scaled_length(std::span<const double> v, double& largest) {
    largest = std::max({std::abs(v[0]), std::abs(v[1]), std::abs(v[2])});
    if (largest == 0) return 0;
    const double x = v[0] / largest, y = v[1] / largest, z = v[2] / largest;
    return std::sqrt(x * x + y * y + z * z);
}

RuntimeValue sqrt_of(const BuiltinArguments& args) {
    const double x = args.number(0);
    if (x < 0) throw BuiltinError{args.span(0), "sqrt of a negative number (" + format_number(x) + ")"};
    return RuntimeValue::number(std::sqrt(x));
}

RuntimeValue str_of(const BuiltinArguments& args) {
    std::string text = value_text(args[0]);
    if (text.size() > kMaxStringBytes)
        throw BuiltinError{args.span(0), "its text would be longer than " + format_number(double(kMaxStringBytes)) +
                                             " characters (the limit)"};
    return RuntimeValue::string(std::move(text));
}

RuntimeValue mod_of(const BuiltinArguments& args) {
    const double a = args.number(0), b = args.number(1);
    if (b == 0) throw BuiltinError{args.span(1), "mod by zero"};
    const double r = std::fmod(a, b);
    return RuntimeValue::number(r != 0 && (r < 0) != (b < 0) ? r + b : r);  // the divisor's sign
}

RuntimeValue abs_of(const BuiltinArguments& args) {
    if (!args[0].is_vector()) return RuntimeValue::number(std::abs(args.number(0)));
    std::vector<double> out;
    for (double c : args[0].components()) out.push_back(std::abs(c));
    return RuntimeValue::vector(out);
}

RuntimeValue length_of(const BuiltinArguments& args) {
    double largest;
    const double length = scaled_length(args.vector(0), largest);
    return RuntimeValue::number(largest * length);
}

RuntimeValue normalize_of(const BuiltinArguments& args) {
    std::span<const double> v = args.vector(0);
    double largest;
    const double length = scaled_length(v, largest);
    if (largest == 0) throw BuiltinError{args.span(0), "normalize of the zero vector"};
    return RuntimeValue::vector3(v[0] / largest / length, v[1] / largest / length, v[2] / largest / length);
}

RuntimeValue pow_of(const BuiltinArguments& args) {
    const double base = args.number(0), exponent = args.number(1);
    if (base < 0 && std::floor(exponent) != exponent)
        throw BuiltinError{args.span(1), "pow of a negative number (" + format_number(base) +
                                             ") to a power that is not whole (" + format_number(exponent) + ")"};
    if (base == 0 && exponent < 0)
        throw BuiltinError{args.span(1), "pow of 0 to a negative power (" + format_number(exponent) + ")"};
    return RuntimeValue::number(std::pow(base, exponent));
}

RuntimeValue log_of(const BuiltinArguments& args) {
    const double x = args.number(0);
    if (x <= 0) throw BuiltinError{args.span(0), "log of a number not above 0 (" + format_number(x) + ")"};
    return RuntimeValue::number(std::log(x));
}

// asin and acos, in degrees, of a number in [-1, 1].
RuntimeValue inverse_sine_or_cosine(const BuiltinArguments& args, bool sine) {
    const double x = args.number(0);
    if (x < -1 || x > 1)
        throw BuiltinError{args.span(0), std::string(sine ? "asin" : "acos") + " of a number outside -1..1 (" +
                                             format_number(x) + ")"};
    return RuntimeValue::number((sine ? std::asin(x) : std::acos(x)) / kRadians);
}

RuntimeValue atan2_of(const BuiltinArguments& args) {
    const double y = args.number(0), x = args.number(1);
    if (x == 0 && y == 0) throw BuiltinError{args.call(), "atan2 of (0, 0): the angle of the zero vector"};
    return RuntimeValue::number(std::atan2(y, x) / kRadians);
}

// SplitMix64's finaliser (Steele, Lea and Flood 2014): a bijection of 64-bit words whose
// outputs pass BigCrush; integer arithmetic only, so every machine gives the same bits.
uint64_t mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

// The IEEE-754 bits of a number, with -0 taken as 0.
uint64_t bits_of(double x) {
    if (x == 0) x = 0;
    uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    return bits;
}

RuntimeValue random_of(const BuiltinArguments& args) {
    const uint64_t word = mix64(bits_of(args.number(0)) ^ mix64(bits_of(args.number(1)) + 0x9e3779b97f4a7c15ULL));
    return RuntimeValue::number(double(word >> 11) * 0x1.0p-53);  // the top 53 bits: [0, 1)
}

RuntimeValue noise_of(const BuiltinArguments& args) {
    const std::span<const double> p = args.vector(0);
    return RuntimeValue::number(improved_noise({p[0], p[1], p[2]}));
}

RuntimeValue turbulence_of(const BuiltinArguments& args) {
    const std::span<const double> p = args.vector(0);
    const double octaves = args.number(1);
    if (!(octaves >= 1 && octaves <= kMaxOctaves) || std::floor(octaves) != octaves)
        throw BuiltinError{args.span(1), "turbulence takes a whole number of octaves from 1 to " +
                                             std::to_string(kMaxOctaves) + ", not " + format_number(octaves)};
    return RuntimeValue::number(turbulence({p[0], p[1], p[2]}, int(octaves)));
}

RuntimeValue cross_of(const BuiltinArguments& args) {
    const std::span<const double> a = args.vector(0), b = args.vector(1);
    return RuntimeValue::vector3(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
}

RuntimeValue lerp_of(const BuiltinArguments& args) {
    const double t = args.number(2);
    if (args[0].is_number() && args[1].is_number())
        return RuntimeValue::number(args[0].x[0] + (args[1].x[0] - args[0].x[0]) * t);
    const std::span<const double> a = args.vector(0), b = args.vector(1);
    return RuntimeValue::vector3(a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t);
}

}  // namespace

const std::vector<Builtin>& all_builtins() {
    using Args = const BuiltinArguments&;
    // clang-format off
    static const std::vector<Builtin> builtins = {
        {"sqrt", 1, "Square root (of a number not below 0).", sqrt_of},
        {"sin", 1, "Sine of an angle in degrees.",
         [](Args args) { return RuntimeValue::number(std::sin(args.number(0) * kRadians)); }},
        {"cos", 1, "Cosine of an angle in degrees.",
         [](Args args) { return RuntimeValue::number(std::cos(args.number(0) * kRadians)); }},
        {"tan", 1, "Tangent of an angle in degrees.",
         [](Args args) { return RuntimeValue::number(std::tan(args.number(0) * kRadians)); }},
        {"abs", 1, "Absolute value, of a number or of each component of a vector.", abs_of},
        {"floor", 1, "The largest whole number not above.",
         [](Args args) { return RuntimeValue::number(std::floor(args.number(0))); }},
        {"min", 2, "The smaller of two numbers.",
         [](Args args) { return RuntimeValue::number(std::min(args.number(0), args.number(1))); }},
        {"max", 2, "The larger of two numbers.",
         [](Args args) { return RuntimeValue::number(std::max(args.number(0), args.number(1))); }},
        {"mod", 2, "Remainder of a / b, with b's sign: mod(-1, 3) is 2.", mod_of},
        {"length", 1, "Length of a vector.", length_of},
        {"normalize", 1, "The vector scaled to length 1 (not the zero vector).", normalize_of},
        {"dot", 2, "Dot product of two vectors.",
         [](Args args) {
             const std::span<const double> a = args.vector(0), b = args.vector(1);
             return RuntimeValue::number(a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
         }},
        {"cross", 2, "Cross product of two vectors (right-handed).", cross_of},
        {"lerp", 3, "lerp(a, b, t) = a + (b - a) t, of numbers or of vectors.", lerp_of},
        {"pow", 2, "pow(a, b) = a to the power b (a negative a takes a whole b; 0 takes b >= 0).", pow_of},
        {"exp", 1, "e to the power of a number.",
         [](Args args) { return RuntimeValue::number(std::exp(args.number(0))); }},
        {"log", 1, "Natural logarithm of a number above 0.", log_of},
        {"asin", 1, "Inverse sine, in degrees (-90 to 90), of a number in -1..1.",
         [](Args args) { return inverse_sine_or_cosine(args, true); }},
        {"acos", 1, "Inverse cosine, in degrees (0 to 180), of a number in -1..1.",
         [](Args args) { return inverse_sine_or_cosine(args, false); }},
        {"atan", 1, "Inverse tangent, in degrees (-90 to 90).",
         [](Args args) { return RuntimeValue::number(std::atan(args.number(0)) / kRadians); }},
        {"atan2", 2, "atan2(y, x): the angle of the point (x, y) from the x axis, in degrees (-180 to 180].",
         atan2_of},
        {"random", 2,
         "random(seed, i): a number in [0, 1), the same for the same two numbers on every machine, "
         "unrelated for different ones (SplitMix64 of their bits; see grammar/README.md).",
         random_of},
        {"noise", 1,
         "noise(p): Perlin's improved noise (2002) at the point p, within about -1..1, 0 on the integer "
         "lattice; the exact definition is in src/scene/noise.h and grammar/README.md.",
         noise_of},
        {"turbulence", 2,
         "turbulence(p, octaves): the sum over octaves i = 0, 1, ... of |noise(2^i p)| / 2^i (Perlin, "
         "1985), 1 to 30 octaves; 0 or more, below 2.",
         turbulence_of},
        {"str", 1,
         "The value as text: numbers in the shortest form that reads back exactly (0.1, 1e-30), "
         "vectors (1, 2, 3), lists [1, \"a\"], booleans true and false; a string as it is.",
         str_of},
        {"len", 1, "The number of values in a list.",
         [](Args args) { return RuntimeValue::number(double(args.list(0).size())); }},
    };
    // clang-format on
    return builtins;
}

const std::vector<BuiltinConstant>& all_constants() {
    static const std::vector<BuiltinConstant> constants = {
        {"pi", std::numbers::pi, "The ratio of a circle's circumference to its diameter, 3.14159..."},
        {"clock", 0,
         "The animation's time at this frame: from the first clock value at frame 0 to the last at the last "
         "frame (0 to 1 unless `--clock` says otherwise; 0 in a still image)",
         FrameValue::Clock},
        {"clock_delta", 0, "How far `clock` moves from one frame to the next (0 in a still image)",
         FrameValue::ClockDelta},
        {"frame_number", 0, "The frame's number, from 0 (0 in a still image)", FrameValue::FrameNumber},
    };
    return constants;
}

const BuiltinConstant* find_constant(std::string_view name) {
    for (const BuiltinConstant& constant : all_constants())
        if (constant.name == name) return &constant;
    return nullptr;
}

const Builtin* find_builtin(std::string_view name) {
    for (const Builtin& builtin : all_builtins())
        if (builtin.name == name) return &builtin;
    return nullptr;
}

}  // namespace tracer
