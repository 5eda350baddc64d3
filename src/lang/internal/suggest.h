// "Did you mean ...?" for misspelled names.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace tracer {

// Edit distance with adjacent transpositions (optimal string alignment), ignoring case.
int edit_distance(std::string_view a, std::string_view b);

// The candidate that `word` means in another renderer's vocabulary ("specular": "ks"), else
// the candidate closest to it if close enough to be a likely typo, else "".
std::string closest_match(std::string_view word, const std::vector<std::string_view>& candidates);

// True for a word meant as NaN or infinity ("nan", "Inf", "infinity"), which the language does not
// allow: messages about such a word say so.
bool names_nan_or_infinity(std::string_view word);

// "; did you mean 'x'?" or "" — to append to a message.
std::string did_you_mean(std::string_view word, const std::vector<std::string_view>& candidates);

// For a word of POV-Ray's scene language that tracer spells otherwise or does not have (a block
// kind or a key: union, pigment, area_light, ...), "; " and how to write it here; else "".
std::string povray_hint(std::string_view word);

}  // namespace tracer
