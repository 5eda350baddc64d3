// What C++20 gives but the browser build's standard library (emscripten 3.1's libc++) lacks:
// std::bit_cast, and std::from_chars and std::to_chars for floating point. Where the library has
// them they are used; the stand-ins are built everywhere, and the unit tests hold them to the
// library's own (tests/unit/base/portable_test.cpp).
#pragma once

#include <charconv>
#include <type_traits>

namespace tracer {

// std::bit_cast: the bits of `from` as a To.
template <typename To, typename From>
constexpr To bit_cast(const From& from) noexcept {
    static_assert(sizeof(To) == sizeof(From) && std::is_trivially_copyable_v<From>);
    return __builtin_bit_cast(To, from);
}

// std::from_chars(first, last, value) for a double, in its default (general) format, by strtod:
// no leading '+' or space, no "0x"; out of range (overflow, or underflow to zero) as
// std::errc::result_out_of_range.
std::from_chars_result parse_double_by_strtod(const char* first, const char* last, double& value);

// std::to_chars(first, last, value) for a double, by printf: the shortest text that reads back as
// `value`, in fixed or exponent form, whichever is shorter (fixed on a tie).
std::to_chars_result shortest_chars_by_printf(char* first, char* last, double value);

#if defined(_LIBCPP_VERSION) && _LIBCPP_VERSION < 170000
#define TRACER_NO_FLOAT_CHARCONV 1
#endif

// std::from_chars for a double (its stand-in where the library has none).
inline std::from_chars_result parse_double(const char* first, const char* last, double& value) {
#if defined(TRACER_NO_FLOAT_CHARCONV)
    return parse_double_by_strtod(first, last, value);
#else
    return std::from_chars(first, last, value);
#endif
}

// std::to_chars for a double, its shortest form (its stand-in where the library has none).
inline std::to_chars_result shortest_chars(char* first, char* last, double value) {
#if defined(TRACER_NO_FLOAT_CHARCONV)
    return shortest_chars_by_printf(first, last, value);
#else
    return std::to_chars(first, last, value);
#endif
}

}  // namespace tracer
