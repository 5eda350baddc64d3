// Patterns: colour that varies over a surface, as a material's kd or ka (docs/guide/patterns.md).
// A pattern is a function from a point of its own space to a colour. The point comes from the
// shape's own coordinates (the ones its block is written in, before its placement and its
// groups'), carried into the pattern's space by the inverse of the pattern's own steps, then,
// for the 2D mappings, flattened to (u, v, 0); `uv` mapping starts from the surface's own (u, v)
// instead (World::surface_uv). A checker's squares may themselves be patterns, evaluated at the
// same point in the checker's space (their steps apply after the checker's).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "base/diagnostics.h"

namespace tracer {

// p -> linear p + offset.
struct Affine {
    glm::dmat3 linear{1.0};
    glm::dvec3 offset{0.0};
    // linear * p + offset in glm's order, inlined: as glm's call, every pattern lookup waited
    // on the vector it returned through memory.
    [[gnu::always_inline]] glm::dvec3 operator()(const glm::dvec3& p) const {
        const glm::dmat3& m = linear;
        return glm::dvec3(m[0][0] * p.x + m[1][0] * p.y + m[2][0] * p.z, m[0][1] * p.x + m[1][1] * p.y + m[2][1] * p.z,
                          m[0][2] * p.x + m[1][2] * p.y + m[2][2] * p.z) +
               offset;
    }
    bool operator==(const Affine&) const = default;
};

// What a pattern computes; every kind but checker and image looks its value up in a colour map.
enum class PatternKind : uint8_t { Checker, Stripes, Gradient, Rings, Spots, Turbulence, Marble, Wood, Image };
// How a point becomes the pattern's coordinates: itself (solid), or flattened to (u, v, 0).
enum class Mapping : uint8_t { Solid, Planar, Spherical, Cylindrical, Uv };
// What an image shows outside 0..1.
enum class Wrap : uint8_t { Repeat, Clamp, Mirror };

// The scene-language word of each (one table each in pattern.cpp), and back (false if unknown).
const char* pattern_kind_name(PatternKind kind);
bool pattern_kind_from_name(std::string_view name, PatternKind& out);
const char* mapping_name(Mapping mapping);
bool mapping_from_name(std::string_view name, Mapping& out);
const char* wrap_name(Wrap wrap);
bool wrap_from_name(std::string_view name, Wrap& out);

// A point of a colour map: the value `at` (0..1) where the colour is `color`.
struct ColorStop {
    double at = 0;
    glm::dvec3 color{0.0};
    bool operator==(const ColorStop&) const = default;
};

// The most stops a colour map may hold.
constexpr size_t kMostColorStops = 65536;
// The largest file an image pattern may name (a PNG of 16384 x 16384 texels is far less): the
// language refuses a larger one at its `file` value, and the loader checks again.
constexpr uint64_t kMaxImageFileBytes = uint64_t(1) << 30;

// A colour, or the pattern SceneDescription::patterns[pattern] (pattern >= 0).
struct Paint {
    glm::dvec3 color{0.0};
    int pattern = -1;
    bool patterned() const { return pattern >= 0; }
    bool operator==(const Paint&) const = default;
};

struct Pattern {
    PatternKind kind = PatternKind::Checker;
    Mapping mapping = Mapping::Solid;
    Affine to_pattern;               // the inverse of its own steps
    Paint even{glm::dvec3(1.0)};     // checker: where floor(x) + floor(y) + floor(z) is even
    Paint odd{glm::dvec3(0.0)};      // and odd
    std::vector<ColorStop> colors;   // the colour map, stops in order (not checker, image)
    glm::dvec3 axis{0.0, 1.0, 0.0};  // unit: stripes' and gradient's direction, rings' and wood's line
    double turbulence = 0;           // marble, wood: how far turbulence displaces the value
    int octaves = 6;                 // spots, turbulence, marble, wood: octaves of the noise sum
    int image = -1;                  // image: index into SceneDescription::images
    Wrap wrap = Wrap::Repeat;        // image
    glm::dvec3 multiply{1.0};        // every colour it gives, times this (0.1 * pattern)
    bool operator==(const Pattern&) const = default;
};

// An image's texels as read: 8-bit files keep their bytes (decoded from sRGB on lookup), others
// are floats, linear. Row 0 is the top of the picture; `channels` is 1 (grey) or 3 (RGB).
struct Texels {
    int width = 0, height = 0, channels = 3;
    std::vector<uint8_t> bytes;  // 8-bit files
    std::vector<float> floats;   // float files
    size_t memory_bytes() const { return bytes.size() + floats.size() * sizeof(float); }
};

// An image file a pattern names; its texels are filled in when the scene's files are read
// (io/texture_file.h), and shared by every copy of the description.
struct ImageFile {
    std::string path;   // absolute
    Location named_at;  // the `file` value in the scene
    std::shared_ptr<const Texels> texels;
};

// The colour of image texels at (u, v): u across, v up (v = 0 is the picture's bottom row),
// each texel's colour at its center, bilinear between the four around (u, v), outside 0..1 by
// `wrap`. 8-bit values are decoded from sRGB first; black if there are no texels.
glm::dvec3 image_color(const Texels& texels, double u, double v, Wrap wrap);

// The linear value of an sRGB-encoded byte (IEC 61966-2-1).
double srgb_decoded(uint8_t byte);

// True if some pattern maps by the surface's own (u, v) (Mapping::Uv).
bool uses_surface_coordinates(std::span<const Pattern> patterns);
// True if patterns[index], or a pattern inside it, maps by (u, v); false for index -1.
bool maps_by_uv(std::span<const Pattern> patterns, int index);

// The colour of `patterns[index]` at a point of the shape's own coordinates and at its surface
// (u, v) (read only by `uv` mapping), with the images it may read.
glm::dvec3 pattern_color(std::span<const Pattern> patterns, std::span<const ImageFile> images, int index,
                         const glm::dvec3& point, const glm::dvec3& uv);

// True if patterns[a] and patterns[b] give the same colours but for their `multiply` (a
// material's `ka 0.1 * squares  kd squares`): one unscaled_pattern_color serves both.
bool same_but_multiply(std::span<const Pattern> patterns, int a, int b);
// pattern_color before patterns[index]'s own `multiply` (pattern_color is multiply times it).
glm::dvec3 unscaled_pattern_color(std::span<const Pattern> patterns, std::span<const ImageFile> images, int index,
                                  const glm::dvec3& point, const glm::dvec3& uv);
// The colour map's colour at `value`: the first stop's below it, the last's above, linear
// between two stops (the later of stops at one value wins above it); black if empty. Stepped
// (stripes): the colour of the last stop at or below `value`, the first's below them all.
glm::dvec3 color_map_at(std::span<const ColorStop> stops, double value, bool stepped = false);

// The value in 0..1 (before the colour map) of a map pattern at point q of its space.
double pattern_value(const Pattern& pattern, const glm::dvec3& q);

// The point's coordinates by `mapping` (Solid: itself; the others: (u, v, 0)).
glm::dvec3 mapped(Mapping mapping, const glm::dvec3& p);

}  // namespace tracer
