#include "scene/pattern.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "scene/noise.h"
#include "scene/words.h"

namespace tracer {
namespace {

using dvec3 = glm::dvec3;

constexpr Words<PatternKind, 9> kPatternKindWords{{{PatternKind::Checker, "checker"},
                                                   {PatternKind::Stripes, "stripes"},
                                                   {PatternKind::Gradient, "gradient"},
                                                   {PatternKind::Rings, "rings"},
                                                   {PatternKind::Spots, "spots"},
                                                   {PatternKind::Turbulence, "turbulence"},
                                                   {PatternKind::Marble, "marble"},
                                                   {PatternKind::Wood, "wood"},
                                                   {PatternKind::Image, "image"}}};
constexpr Words<Mapping, 5> kMappingWords{{{Mapping::Solid, "solid"},
                                           {Mapping::Planar, "planar"},
                                           {Mapping::Spherical, "spherical"},
                                           {Mapping::Cylindrical, "cylindrical"},
                                           {Mapping::Uv, "uv"}}};
constexpr Words<Wrap, 3> kWrapWords{{{Wrap::Repeat, "repeat"}, {Wrap::Clamp, "clamp"}, {Wrap::Mirror, "mirror"}}};

// A checker's cells are nudged by this (in its own units) so that a surface on a cell boundary,
// a floor at y = 0, takes the cell above it whatever the rounding of its points.
constexpr double kCheckerNudge = 1e-6;

double fraction(double x) {
    return x - std::floor(x);
}

// The distance of q from the line through the origin along unit `axis`.
double distance_from_axis(const dvec3& q, const dvec3& axis) {
    return glm::length(q - glm::dot(q, axis) * axis);
}

// The texel index `i` (of `size`) brought inside the image by `wrap`.
int wrapped(long long i, int size, Wrap wrap) {
    switch (wrap) {
        case Wrap::Repeat: return int(((i % size) + size) % size);
        case Wrap::Clamp: return int(std::clamp<long long>(i, 0, size - 1));
        case Wrap::Mirror: {
            const long long period = 2LL * size;
            const long long m = ((i % period) + period) % period;
            return int(m < size ? m : period - 1 - m);
        }
    }
    return 0;
}

dvec3 texel(const Texels& texels, int x, int y) {
    const size_t at = (size_t(y) * size_t(texels.width) + size_t(x)) * size_t(texels.channels);
    if (!texels.bytes.empty()) {
        if (texels.channels == 1) return dvec3(srgb_decoded(texels.bytes[at]));
        return {srgb_decoded(texels.bytes[at]), srgb_decoded(texels.bytes[at + 1]), srgb_decoded(texels.bytes[at + 2])};
    }
    if (texels.channels == 1) return dvec3(texels.floats[at]);
    return {texels.floats[at], texels.floats[at + 1], texels.floats[at + 2]};
}

// A coordinate beyond this many image widths is folded back first (repeat and mirror have a
// period of at most two widths), so that the texel index fits its integer.
constexpr double kFarthestCoordinate = 1e9;

}  // namespace

const char* pattern_kind_name(PatternKind kind) {
    return word_of(kPatternKindWords, kind);
}
bool pattern_kind_from_name(std::string_view name, PatternKind& out) {
    return value_of(kPatternKindWords, name, out);
}
const char* mapping_name(Mapping mapping) {
    return word_of(kMappingWords, mapping);
}
bool mapping_from_name(std::string_view name, Mapping& out) {
    return value_of(kMappingWords, name, out);
}
const char* wrap_name(Wrap wrap) {
    return word_of(kWrapWords, wrap);
}
bool wrap_from_name(std::string_view name, Wrap& out) {
    return value_of(kWrapWords, name, out);
}

double srgb_decoded(uint8_t byte) {
    static const std::array<double, 256> table = [] {
        std::array<double, 256> values{};
        for (int i = 0; i < 256; ++i) {
            const double v = i / 255.0;
            values[size_t(i)] = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
        }
        return values;
    }();
    return table[byte];
}

dvec3 image_color(const Texels& texels, double u, double v, Wrap wrap) {
    if (texels.width <= 0 || texels.height <= 0) return dvec3(0.0);
    if (!std::isfinite(u) || !std::isfinite(v)) return texel(texels, 0, 0);
    // Texel centers at (i + 0.5) / size; row 0 at the top (v = 1).
    auto fold = [wrap](double s) {
        if (wrap == Wrap::Clamp || std::abs(s) < kFarthestCoordinate) return s;
        return std::fmod(s, 2.0);
    };
    const double x = fold(u) * texels.width - 0.5;
    const double y = (1 - fold(v)) * texels.height - 0.5;
    const double x_floor = std::floor(std::clamp(x, -4e18, 4e18)), y_floor = std::floor(std::clamp(y, -4e18, 4e18));
    const double fx = std::clamp(x - x_floor, 0.0, 1.0), fy = std::clamp(y - y_floor, 0.0, 1.0);
    const int x0 = wrapped((long long)x_floor, texels.width, wrap);
    const int x1 = wrapped((long long)x_floor + 1, texels.width, wrap);
    const int y0 = wrapped((long long)y_floor, texels.height, wrap);
    const int y1 = wrapped((long long)y_floor + 1, texels.height, wrap);
    const dvec3 top = texel(texels, x0, y0) * (1 - fx) + texel(texels, x1, y0) * fx;
    const dvec3 bottom = texel(texels, x0, y1) * (1 - fx) + texel(texels, x1, y1) * fx;
    return top * (1 - fy) + bottom * fy;
}

dvec3 color_map_at(std::span<const ColorStop> stops, double value, bool stepped) {
    if (stops.empty()) return dvec3(0.0);
    if (!(value >= stops.front().at)) return stops.front().color;  // below every stop (or NaN)
    // The last stop at or below the value.
    const auto after = std::upper_bound(stops.begin(), stops.end(), value,
                                        [](double v, const ColorStop& stop) { return v < stop.at; });
    const ColorStop& below = *(after - 1);
    if (stepped || after == stops.end()) return below.color;
    const double t = (value - below.at) / (after->at - below.at);
    return below.color + (after->color - below.color) * t;
}

dvec3 mapped(Mapping mapping, const dvec3& p) {
    constexpr double kTurn = 2 * std::numbers::pi;
    switch (mapping) {
        case Mapping::Solid:
        case Mapping::Uv: return p;
        case Mapping::Planar: return {p.x, p.y, 0};
        case Mapping::Spherical: {
            const double r = glm::length(p);
            const double latitude = r > 0 ? std::asin(std::clamp(p.y / r, -1.0, 1.0)) : 0;
            return {0.5 + std::atan2(p.x, p.z) / kTurn, 0.5 + latitude / std::numbers::pi, 0};
        }
        case Mapping::Cylindrical: return {0.5 + std::atan2(p.x, p.z) / kTurn, p.y, 0};
    }
    return p;
}

double pattern_value(const Pattern& pattern, const dvec3& q) {
    constexpr double kTurn = 2 * std::numbers::pi;
    switch (pattern.kind) {
        case PatternKind::Stripes:
        case PatternKind::Gradient: return fraction(glm::dot(q, pattern.axis));
        case PatternKind::Rings: return fraction(distance_from_axis(q, pattern.axis));
        case PatternKind::Spots: return std::clamp(0.5 + 0.5 * improved_noise(q), 0.0, 1.0);
        case PatternKind::Turbulence: return std::clamp(turbulence(q, pattern.octaves), 0.0, 1.0);
        case PatternKind::Marble:
            return 0.5 + 0.5 * std::sin(kTurn * (glm::dot(q, pattern.axis) +
                                                 pattern.turbulence * turbulence(q, pattern.octaves)));
        case PatternKind::Wood:
            return fraction(distance_from_axis(q, pattern.axis) + pattern.turbulence * turbulence(q, pattern.octaves));
        case PatternKind::Checker:
        case PatternKind::Image: break;
    }
    return 0;
}

bool uses_surface_coordinates(std::span<const Pattern> patterns) {
    return std::any_of(patterns.begin(), patterns.end(),
                       [](const Pattern& pattern) { return pattern.mapping == Mapping::Uv; });
}

bool maps_by_uv(std::span<const Pattern> patterns, int index) {
    if (index < 0) return false;
    const Pattern& pattern = patterns[size_t(index)];
    return pattern.mapping == Mapping::Uv || maps_by_uv(patterns, pattern.even.pattern) ||
           maps_by_uv(patterns, pattern.odd.pattern);
}

bool same_but_multiply(std::span<const Pattern> patterns, int a, int b) {
    if (a < 0 || b < 0) return false;
    Pattern scaled_like_a = patterns[size_t(b)];
    scaled_like_a.multiply = patterns[size_t(a)].multiply;
    return patterns[size_t(a)] == scaled_like_a;
}

dvec3 pattern_color(std::span<const Pattern> patterns, std::span<const ImageFile> images, int index, const dvec3& point,
                    const dvec3& uv) {
    return patterns[size_t(index)].multiply * unscaled_pattern_color(patterns, images, index, point, uv);
}

// A checker's square at q of its space: even where floor(x) + floor(y) + floor(z) is even.
[[gnu::always_inline]] static inline const Paint& checker_square(const Pattern& pattern, const dvec3& q) {
    const double sum =
        std::floor(q.x + kCheckerNudge) + std::floor(q.y + kCheckerNudge) + std::floor(q.z + kCheckerNudge);
    const double half = 0.5 * sum;  // even: a whole number of pairs
    return half == std::floor(half) ? pattern.even : pattern.odd;
}

dvec3 unscaled_pattern_color(std::span<const Pattern> patterns, std::span<const ImageFile> images, int index,
                             const dvec3& point, const dvec3& uv) {
    const Pattern& pattern = patterns[size_t(index)];
    // A solid checker of two colours (a floor's squares), its point kept in registers: through
    // the general path below it went by the stack, and its loads waited on wider stores.
    if (pattern.kind == PatternKind::Checker && pattern.mapping == Mapping::Solid && !pattern.even.patterned() &&
        !pattern.odd.patterned())
        return checker_square(pattern, pattern.to_pattern(point)).color;
    const dvec3 own_point = pattern.to_pattern(point);
    // The surface's (u, v) in this pattern's space, where it or a pattern inside it reads them.
    const bool uv_read = pattern.mapping == Mapping::Uv || pattern.even.patterned() || pattern.odd.patterned();
    const dvec3 own_uv = uv_read ? pattern.to_pattern(uv) : uv;
    const dvec3 q = pattern.mapping == Mapping::Uv ? own_uv : mapped(pattern.mapping, own_point);
    switch (pattern.kind) {
        case PatternKind::Checker: {
            const Paint& square = checker_square(pattern, q);
            return square.patterned() ? pattern_color(patterns, images, square.pattern, own_point, own_uv)
                                      : square.color;
        }
        case PatternKind::Image: {
            const ImageFile& image = images[size_t(pattern.image)];
            return image.texels ? image_color(*image.texels, q.x, q.y, pattern.wrap) : dvec3(0.0);
        }
        default: return color_map_at(pattern.colors, pattern_value(pattern, q), pattern.kind == PatternKind::Stripes);
    }
}

}  // namespace tracer
