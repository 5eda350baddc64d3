// The stand-ins of base/portable.h (used by the browser's build, whose standard library lacks
// floating-point charconv) give the standard library's own answers: text for text, value for value.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "base/portable.h"

namespace tracer {
namespace {

std::string standard_text(double value) {
    char text[64];
    return std::string(text, std::to_chars(text, text + sizeof text, value).ptr);
}

std::string stand_in_text(double value) {
    char text[64];
    return std::string(text, shortest_chars_by_printf(text, text + sizeof text, value).ptr);
}

std::vector<double> awkward_values() {
    std::vector<double> values{0.0,
                               -0.0,
                               1.0,
                               -1.0,
                               0.5,
                               0.1,
                               0.2,
                               0.3,
                               1.0 / 3,
                               2.0 / 3,
                               10,
                               100,
                               1e15,
                               1e16,
                               1e20,
                               1e21,
                               1e22,
                               1e23,
                               123456789012345678.0,
                               0.001,
                               0.0001,
                               1e-5,
                               1e-7,
                               1.5e-300,
                               5e-324,
                               2.2250738585072014e-308,
                               1.7976931348623157e308,
                               9007199254740993.0,
                               std::numeric_limits<double>::infinity(),
                               -std::numeric_limits<double>::infinity(),
                               1234.5,
                               0.000123,
                               12e3,
                               4.35,
                               0.07,
                               255.0 / 256};
    std::mt19937_64 random(59);
    for (int i = 0; i < 20000; ++i) {
        uint64_t bits = random();
        double value;
        std::memcpy(&value, &bits, sizeof value);
        if (std::isfinite(value)) values.push_back(value);
        values.push_back(std::ldexp(double(random() % 100000) / 1000, int(random() % 60) - 30));
    }
    return values;
}

TEST(Portable, ShortestTextIsTheStandardLibrarys) {
    for (const double value : awkward_values()) ASSERT_EQ(stand_in_text(value), standard_text(value)) << value;
}

TEST(Portable, ParsedNumbersAreTheStandardLibrarys) {
    std::vector<std::string> texts{"0",        "-0",
                                   "1",        "1.5",
                                   ".5",       "5.",
                                   "1e5",      "1E-5",
                                   "-2.5e+3",  "1e400",
                                   "1e-400",   "-1e400",
                                   "inf",      "-infinity",
                                   "nan",      "0x10",
                                   "+1",       " 1",
                                   "-",        "",
                                   "e5",       "1e",
                                   "1.2.3",    "12abc",
                                   "4.9e-324", "2.4703282292062328e-324",
                                   "017",      "-.e1"};
    for (const double value : awkward_values()) texts.push_back(standard_text(value));
    for (const std::string& text : texts) {
        double standard = -7, stand_in = -7;
        const char* first = text.data();
        const char* last = first + text.size();
        const auto want = std::from_chars(first, last, standard);
        const auto got = parse_double_by_strtod(first, last, stand_in);
        ASSERT_EQ(int(got.ec), int(want.ec)) << "'" << text << "'";
        ASSERT_EQ(got.ptr - first, want.ptr - first) << "'" << text << "'";
        if (want.ec == std::errc() && !std::isnan(standard)) {
            ASSERT_EQ(std::memcmp(&stand_in, &standard, sizeof standard), 0) << "'" << text << "'";
        }
    }
}

TEST(Portable, BitCastGivesTheBits) {
    EXPECT_EQ(bit_cast<uint32_t>(1.0f), 0x3f800000u);
    EXPECT_EQ(bit_cast<double>(uint64_t(0x3ff0000000000000)), 1.0);
}

}  // namespace
}  // namespace tracer
