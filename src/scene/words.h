// Tables of a setting's values and their scene-language words (the render block's choices, the
// patterns' kinds and mappings): one row per value, looked up both ways.
#pragma once

#include <array>
#include <string_view>
#include <utility>

namespace tracer {

// A choice's values and their words, in the order of the enum.
template <typename Enum, size_t N>
using Words = std::array<std::pair<Enum, const char*>, N>;

// The word of `value` (the first row's if it has none).
template <typename Enum, size_t N>
const char* word_of(const Words<Enum, N>& words, Enum value) {
    for (const auto& [each, word] : words)
        if (each == value) return word;
    return words[0].second;
}

// The value whose word is `word` into `out`; false if none.
template <typename Enum, size_t N>
bool value_of(const Words<Enum, N>& words, std::string_view word, Enum& out) {
    for (const auto& [each, each_word] : words)
        if (word == each_word) {
            out = each;
            return true;
        }
    return false;
}

}  // namespace tracer
