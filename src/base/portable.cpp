#include "base/portable.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace tracer {

std::from_chars_result parse_double_by_strtod(const char* first, const char* last, double& value) {
    // strtod (correctly rounded, as from_chars) on a terminated copy, held to from_chars' forms.
    const std::string text(first, last);
    const size_t sign = !text.empty() && text[0] == '-' ? 1 : 0;
    const char lead = sign < text.size() ? text[sign] : '\0';
    if (!std::isdigit(static_cast<unsigned char>(lead)) && lead != '.' && lead != 'i' && lead != 'I' && lead != 'n' &&
        lead != 'N')
        return {first, std::errc::invalid_argument};
    if (lead == '0' && sign + 1 < text.size() && (text[sign + 1] | 0x20) == 'x') {  // from_chars stops at the 'x'
        value = sign ? -0.0 : 0.0;
        return {first + sign + 1, std::errc()};
    }
    errno = 0;
    char* end = nullptr;
    const double parsed = std::strtod(text.c_str(), &end);
    const char* stop = first + (end - text.c_str());
    if (stop == first) return {first, std::errc::invalid_argument};
    if (errno == ERANGE && (parsed == 0 || std::isinf(parsed))) return {stop, std::errc::result_out_of_range};
    value = parsed;
    return {stop, std::errc()};
}

std::to_chars_result shortest_chars_by_printf(char* first, char* last, double value) {
    // The fewest significant digits that read back (printf rounds correctly, so they are the
    // closest such digits, as to_chars' are), then both forms written from them.
    char scientific[40];
    int precision = 0;
    for (; precision < 17; ++precision) {
        std::snprintf(scientific, sizeof scientific, "%.*e", precision, value);
        if (std::strtod(scientific, nullptr) == value) break;
    }
    if (!std::isfinite(value)) {
        const char* word = std::isnan(value) ? (std::signbit(value) ? "-nan" : "nan") : (value < 0 ? "-inf" : "inf");
        const size_t length = std::strlen(word);
        std::memcpy(first, word, length);
        return {first + length, std::errc()};
    }
    std::string digits, sign = std::signbit(value) ? "-" : "";
    const char* mark = std::strchr(scientific, 'e');
    for (const char* c = scientific; c != mark; ++c)
        if (std::isdigit(static_cast<unsigned char>(*c))) digits += *c;
    const int exponent = std::atoi(mark + 1);
    const int count = int(digits.size());
    std::string fixed = sign;
    if (exponent >= count - 1) {  // a whole number: its exact digits, as to_chars writes them
        char whole[400];
        std::snprintf(whole, sizeof whole, "%.0f", std::fabs(value));
        fixed += whole;
    } else if (exponent >= 0) {
        fixed += digits.substr(0, size_t(exponent + 1)) + "." + digits.substr(size_t(exponent + 1));
    } else {
        fixed += "0." + std::string(size_t(-exponent - 1), '0') + digits;
    }
    char power[16];
    std::snprintf(power, sizeof power, "e%c%02d", exponent < 0 ? '-' : '+', std::abs(exponent));
    const std::string exponential = sign + digits.substr(0, 1) + (count > 1 ? "." + digits.substr(1) : "") + power;
    const std::string& chosen = exponential.size() < fixed.size() ? exponential : fixed;
    if (chosen.size() > size_t(last - first)) return {last, std::errc::value_too_large};
    std::memcpy(first, chosen.data(), chosen.size());
    return {first + chosen.size(), std::errc()};
}

}  // namespace tracer
