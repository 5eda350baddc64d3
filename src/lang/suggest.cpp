#include "lang/internal/suggest.h"

#include <algorithm>
#include <cctype>

namespace tracer {

int edit_distance(std::string_view a, std::string_view b) {
    // Optimal string alignment distance, case-insensitive (ASCII), in three rolling rows: it runs
    // for every unknown word of a scene, so it allocates nothing.
    constexpr size_t kLongest = 64;
    if (a.size() > kLongest || b.size() > kLongest) return int(std::max(a.size(), b.size()));
    auto lower = [](char c) { return c >= 'A' && c <= 'Z' ? char(c - 'A' + 'a') : c; };
    const size_t n = a.size(), m = b.size();
    int before[kLongest + 1], previous[kLongest + 1], current[kLongest + 1];
    for (size_t j = 0; j <= m; ++j) previous[j] = int(j);
    for (size_t i = 1; i <= n; ++i) {
        current[0] = int(i);
        for (size_t j = 1; j <= m; ++j) {
            const int cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
            current[j] = std::min({previous[j] + 1, current[j - 1] + 1, previous[j - 1] + cost});
            if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) && lower(a[i - 2]) == lower(b[j - 1]))
                current[j] = std::min(current[j], before[j - 2] + 1);
        }
        std::copy(previous, previous + m + 1, before);
        std::copy(current, current + m + 1, previous);
    }
    return previous[m];
}

// Names other renderers and textbooks use (POV-Ray, pbrt, Mitsuba, RTIOW), and the names this
// language has for the same thing; the first one among the candidates is suggested.
struct Synonym {
    std::string_view word;
    std::vector<std::string_view> ours;
};
static const std::vector<Synonym>& synonyms() {
    static const std::vector<Synonym> table = {
        {"ambient", {"ka"}},
        {"diffuse", {"kd"}},
        {"specular", {"ks"}},
        {"phong", {"ks"}},
        {"reflection", {"km"}},
        {"reflect", {"km"}},
        {"mirror", {"km"}},
        {"shininess", {"n"}},
        {"phong_size", {"n"}},
        {"exponent", {"n"}},
        {"transmission", {"kt"}},
        {"transparency", {"kt"}},
        {"refraction", {"kt"}},
        {"eta", {"ior"}},
        {"location", {"eye", "position", "center"}},
        {"pos", {"position", "center"}},
        {"origin", {"eye", "center", "point"}},
        {"from", {"eye"}},
        {"lookfrom", {"eye"}},
        {"look_from", {"eye"}},
        {"at", {"lookat"}},
        {"look_at", {"lookat"}},
        {"target", {"lookat"}},
        {"fov", {"fovy"}},
        {"angle", {"fovy"}},
        {"filename", {"file"}},
        {"path", {"file"}},
        {"spp", {"samples"}},
        {"depth", {"max_depth"}},
        {"maxdepth", {"max_depth"}},
        {"point_light", {"light"}},
        {"pointlight", {"light"}},
        {"light_source", {"light"}},
        {"intensity", {"color"}},
        {"move", {"translate"}},
        {"translation", {"translate"}},
        {"offset", {"translate"}},
        {"rotation", {"rotate"}},
        {"scaling", {"scale"}},
        {"matrix", {"transform"}},
        {"transforms", {"transform"}},
        {"cube", {"box"}},
        {"rectangle", {"quad"}},
        {"parallelogram", {"quad"}},
        {"colour", {"color"}},
        {"radius", {"base_radius"}},  // POV-Ray's cone has two radii; a cylinder's one is radius
    };
    return table;
}

std::string closest_match(std::string_view word, const std::vector<std::string_view>& candidates) {
    for (const Synonym& synonym : synonyms()) {
        if (word.size() != synonym.word.size() || edit_distance(word, synonym.word) != 0) continue;
        for (std::string_view ours : synonym.ours)
            if (std::find(candidates.begin(), candidates.end(), ours) != candidates.end()) return std::string(ours);
    }
    // Allow about one edit per three letters: "radus" -> "radius", but not "x" -> "n".
    int best = std::max(1, int(word.size()) / 3) + 1;
    std::string_view found;
    for (std::string_view candidate : candidates) {
        int distance = edit_distance(word, candidate);
        if (distance < best && distance < int(candidate.size())) {
            best = distance;
            found = candidate;
        }
    }
    return std::string(found);
}

bool names_nan_or_infinity(std::string_view word) {
    std::string lower;
    for (char c : word) lower += char(std::tolower(static_cast<unsigned char>(c)));
    return lower == "nan" || lower == "inf" || lower == "infinity";
}

std::string povray_hint(std::string_view word) {
    // POV-Ray's word, and tracer's way (a row each: the word, then the whole hint).
    static const std::pair<std::string_view, std::string_view> kHints[] = {
        {"inverse", "a solid's outside is written as a difference: difference { box { ... } sphere { ... } }"},
        {"pigment",
         "a colour is the material's kd, a colour or a pattern: material { kd checker { even 1 odd (1, 0, 0) } }"},
        {"texture",
         "a surface is a material, its kd a colour or a pattern: material { ka 0.1 kd marble { } ks 0.5 n 30 }"},
        {"color_map", "a pattern's colour map is its colors: gradient { colors [[0, (1, 0, 0)], [1, 1]] }"},
        {"colour_map", "a pattern's colour map is its colors: gradient { colors [[0, (1, 0, 0)], [1, 1]] }"},
        {"pigment_map", "a checker's squares may be patterns: checker { even marble { } odd 0.2 }"},
        {"image_map", "a picture is the image pattern: material { kd image { file \"earth.png\" mapping uv } }"},
        {"map_type", "an image's mapping is its mapping key: image { file \"earth.png\" mapping spherical }"},
        {"uv_mapping", "a pattern follows the surface's (u, v) with mapping uv: checker { mapping uv }"},
        {"finish", "a finish is the material's ka, kd, ks, n, km: material { kd 0.8 ks 0.5 n 30 }"},
        {"interior", "refraction is the material's kt and ior: material { kt 0.9 ior 1.5 }"},
        {"area_light",
         "an area light is a block of its own: area_light { position (0, 5, 0) edge1 (1, 0, 0) edge2 (0, 0, 1) "
         "samples1 8 samples2 8 }"},
        {"spotlight", "a spotlight is a block of its own: spotlight { position (0, 5, 0) point_at (0, 0, 0) }"},
        {"point_at", "a spotlight is a block of its own: spotlight { position (0, 5, 0) point_at (0, 0, 0) }"},
        {"parallel", "a parallel light is a block of its own: parallel_light { direction (-1, -2, -1) }"},
        {"looks_like",
         "lights are not seen by rays; a quad with ka 1 in an area light's rectangle shows the lamp without "
         "shadowing it"},
        {"light_source", "a light is light { position (x, y, z) color 1 }"},
        {"location", "the camera's position is eye (x, y, z)"},
        {"look_at", "the camera looks at lookat (x, y, z)"},
    };
    for (const auto& [povray, hint] : kHints)
        if (word == povray) return "; " + std::string(hint);
    return "";
}

std::string did_you_mean(std::string_view word, const std::vector<std::string_view>& candidates) {
    std::string match = closest_match(word, candidates);
    return match.empty() ? "" : "; did you mean '" + match + "'?";
}

}  // namespace tracer
