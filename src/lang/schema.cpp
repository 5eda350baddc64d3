#include "lang/schema.h"

#include <charconv>
#include <cmath>

#include "base/portable.h"
#include "scene/noise.h"
#include "scene/scene.h"

namespace tracer {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Key constructors, so each table row reads: name, type, default, range, meaning.
KeySpec key(std::string_view name, ValueType type, std::string_view default_value, std::string_view meaning) {
    KeySpec spec{};
    spec.name = name;
    spec.type = type;
    spec.default_value = default_value;
    spec.meaning = meaning;
    return spec;
}
KeySpec ranged(KeySpec spec, double min, double max, bool min_open = false, bool max_open = false) {
    spec.min = min;
    spec.max = max;
    spec.min_open = min_open;
    spec.max_open = max_open;
    return spec;
}
KeySpec nonzero(KeySpec spec) {
    spec.nonzero = true;
    return spec;
}
KeySpec square(KeySpec spec) {
    spec.perfect_square = true;
    return spec;
}
KeySpec power_of_two(KeySpec spec) {
    spec.power_of_two = true;
    return spec;
}
KeySpec mirror_size(KeySpec spec) {
    spec.mirror_size = true;
    return spec;
}
KeySpec one_of(KeySpec spec, std::vector<std::string_view> choices) {
    spec.choices = std::move(choices);
    return spec;
}
KeySpec nested(KeySpec spec, const BlockSpec* block) {
    spec.block = block;
    return spec;
}

// The block tables, one row per key (clang-format would break each row into one line per field).
// clang-format off
const BlockSpec kRender{
    "render", false, true, Occurs::AtMostOnce,
    "Image and tracing settings. The whole block is optional.",
    {
        ranged(key("width", ValueType::Integer, "1200", "Image width in pixels."), 1, 16384),
        ranged(key("height", ValueType::Integer, "800", "Image height in pixels."), 1, 16384),
        ranged(key("max_depth", ValueType::Integer, "4",
                   "Reflection bounces after the primary hit; the ray that would be one more "
                   "bounce returns black."), 0, 100000),
        square(ranged(key("samples", ValueType::Integer, "1",
                          "Samples per pixel: a perfect square N*N, stratified over the pixel, box "
                          "filter. 1 is one ray through the pixel center."), 1, 4096)),
        ranged(key("background", ValueType::Triple, "0",
                   "Colour of rays that leave the scene."), 0, kInf),
        key("shadows", ValueType::Boolean, "true", "Trace shadow rays to the lights."),
        key("transparent_shadows", ValueType::Boolean, "false",
            "Let shadow rays through transmitting surfaces (kt > 0): the light is multiplied by kt at "
            "each surface the shadow ray crosses, in a straight line (no refraction, so no caustics). "
            "`false`: every surface blocks light."),
        one_of(key("spawn_rules", ValueType::Choice, "tracer",
                   "Which rays a hit spawns. `tracer`: a reflection ray where the path's mirror weight "
                   "is not zero, a shadow ray where a light's Phong term is not zero, no refracted ray "
                   "under 1/4096 of weight. `spd`: the Standard Procedural Databases' testing "
                   "procedure, for comparing ray counts: a reflection ray at every hit on a surface "
                   "with km or kt above 0, a shadow ray only where the normal faces the light (so a "
                   "light behind the surface lights no highlight there), no weight cut-off."),
               {spawn_rules_name(SpawnRules::Tracer), spawn_rules_name(SpawnRules::Spd)}),
        one_of(key("antialias", ValueType::Choice, "uniform",
                   "How a pixel's samples are placed. `uniform`: `samples` (N*N) in every pixel. "
                   "`adaptive`: one sample at each pixel corner, shared with the neighbours; a cell "
                   "whose corners differ by at least `adaptive_threshold` in a channel is split into "
                   "four, down to `adaptive_depth` levels; a cell's colour is the mean of its corners "
                   "(threshold 0 splits every cell to the full depth). Cells start `adaptive_cell` pixels "
                   "wide. The image is the same for any thread count, tile or region."),
               {antialias_name(Antialias::Uniform), antialias_name(Antialias::Adaptive)}),
        ranged(key("adaptive_threshold", ValueType::Number, "0.05",
                   "With `antialias adaptive`: the difference in one colour channel (clamped to 0..1; "
                   "one level of an 8-bit image is 1/255) at which a cell is split."), 0, 1),
        ranged(key("adaptive_depth", ValueType::Integer, "3",
                   "With `antialias adaptive`: the most times a pixel is split, into 2^depth x 2^depth "
                   "cells at most ((2^depth + 1)^2 samples)."), 0, 8),
        power_of_two(ranged(key("adaptive_cell", ValueType::Number, "1",
                                "With `antialias adaptive`: the side, in pixels, of the cells sampling "
                                "starts from, a power of two from 1/2^adaptive_depth to 16. 1: a pixel's "
                                "corners. Above 1, flat areas take less than a ray per pixel (a pixel in a "
                                "cell left whole is its corners' bilinear blend), and a detail smaller than "
                                "a cell can be missed whole; below 1, every pixel is split at least that far."),
                            1.0 / 256, 16)),
        one_of(key("accel", ValueType::Choice, "sah",
                   "How rays find a mesh's triangles: `none` tests every triangle, `box` one bounding "
                   "box around the mesh, `median` a BVH split at the median centroid (x, y, z by "
                   "depth), `sah` a BVH built with the surface-area heuristic. Objects (spheres, "
                   "meshes) are found through a BVH of their own unless there are at most 8, or "
                   "`none` asks for every one to be tested."),
               {accelerator_name(Accelerator::None), accelerator_name(Accelerator::Box),
                accelerator_name(Accelerator::Median), accelerator_name(Accelerator::Sah)}),
        ranged(key("leaf_size", ValueType::Integer, "4",
                   "Most triangles in a BVH leaf (`median` splits every larger node; `sah` may stop "
                   "earlier where splitting does not pay)."), 1, 255),
        one_of(key("encoding", ValueType::Choice, "linear",
                   "How 8-bit image files (PNG, JPEG, TIFF, BMP) hold the computed colours. `linear`: "
                   "round(255 v) of each value clamped to 0..1, as the assignment's Figure 1 was made "
                   "(an image viewer shows it darker than the light computed). `srgb`: each value "
                   "encoded by the sRGB curve first (12.92 v up to 0.0031308, else 1.055 v^(1/2.4) - "
                   "0.055) and a PNG marked sRGB, so that viewers show the light as computed, as "
                   "POV-Ray's `assumed_gamma 1.0` output and Mitsuba's PNGs are. Float files (EXR, "
                   "HDR, PFM) hold the linear values either way."),
               {encoding_name(Encoding::Linear), encoding_name(Encoding::Srgb)}),
    },
    "render {\n  width 600\n  height 400\n  max_depth 4\n  background (0, 0, 0)\n}\n",
};

const BlockSpec kCamera{
    "camera", false, true, Occurs::ExactlyOnce,
    "A pinhole camera.",
    {
        key("eye", ValueType::Vector, "", "Position of the eye."),
        key("lookat", ValueType::Vector, "", "The point at the center of the image."),
        nonzero(key("up", ValueType::Vector, "(0, 1, 0)",
                    "Which way is up; must not be parallel to the viewing direction.")),
        ranged(key("fovy", ValueType::Number, "45", "Vertical field of view in degrees."), 0, 180,
               true, true),
        ranged(key("focal", ValueType::Number, "1",
                   "Distance from the eye to the image plane (it does not change the image)."),
               0, kInf, true),
    },
    "camera {\n  eye (0, 0, 7)\n  lookat (0, 0, 0)\n  up (0, 1, 0)\n  fovy 45\n}\n",
};

const BlockSpec kMaterial{
    "material", true, true, Occurs::Any,
    "A named Phong material, used by shapes as `material NAME`. The same keys may be written "
    "inline in a shape: `material { kd 0.5 }`. Leaving every key out gives a black material.",
    {
        ranged(key("ka", ValueType::Paint, "0",
                   "Ambient colour, added once and never shadowed; or a pattern (`ka checker { ... }`)."), 0, kInf),
        ranged(key("kd", ValueType::Paint, "0", "Diffuse colour; or a pattern (`kd marble { ... }`)."), 0, kInf),
        ranged(key("ks", ValueType::Triple, "0", "Specular colour."), 0, kInf),
        ranged(key("km", ValueType::Triple, "0",
                   "Mirror reflectance, 0 to 1: the weight of the reflected ray (a surface passes on at most the "
                   "light that reaches it, so that no product of weights along a ray grows)."),
               0, 1),
        ranged(key("n", ValueType::Number, "1", "Phong exponent of the specular highlight."), 0, kInf),
        ranged(key("kt", ValueType::Triple, "0",
                   "Transmittance, 0 to 1: weight of the refracted ray (Snell's law; on total internal "
                   "reflection it goes to the reflected ray), and of a shadow ray through the surface."),
               0, 1),
        ranged(key("ior", ValueType::Number, "1",
                   "Index of refraction inside the surface (outside is 1): 1.5 for glass, 1.33 for water."),
               0, kInf, true),
    },
    "material shiny_green {\n  ka 0.1\n  kd (0.2, 1.0, 0.2)\n  ks 1\n  n 100\n}\n"
    "sphere {\n  center (0, 0, 0)\n  radius 1\n  material shiny_green\n}\n",
};

const BlockSpec kPlane{
    "plane", false, true, Occurs::Any,
    "An infinite plane, visible from both sides.",
    {
        key("point", ValueType::Vector, "", "Any point on the plane."),
        nonzero(key("normal", ValueType::Vector, "", "The plane's normal (normalised for you).")),
        key("material", ValueType::MaterialRef, "", "A material name or an inline material block."),
    },
    "plane {\n  point (0, -1, 0)\n  normal (0, 1, 0)\n  material { ka 0.1 kd 1 }\n}\n",
};

const BlockSpec kRotate{
    "rotate", false, false, Occurs::AtMostOnce,
    "A rotation about an axis through the origin (inside a placed shape or a `transform`).",
    {
        nonzero(key("axis", ValueType::Vector, "(0, 1, 0)", "Rotation axis (normalised for you).")),
        key("angle", ValueType::Number, "0", "Angle in degrees, counter-clockwise looking down the axis."),
    },
    "",
};

KeySpec scale_key(std::string_view meaning) {
    return mirror_size(key("scale", ValueType::Triple, "1", meaning));
}
KeySpec rotate_key(std::string_view meaning) {
    return nested(key("rotate", ValueType::Block, "{ axis (0, 1, 0) angle 0 }", meaning), &kRotate);
}

const BlockSpec kTransform{
    "transform", false, false, Occurs::AtMostOnce,
    "Steps that place a shape, applied in the order written; each key may appear any number of "
    "times. A shape's or a group's own steps are the same; a `transform` among them (a named one, "
    "most often) puts its steps at its place in the chain.",
    {
        scale_key("Scale about the origin, uniform or per axis; a negative factor mirrors."),
        rotate_key("Rotate about an axis through the origin: `rotate { axis (x, y, z) angle degrees }`."),
        key("translate", ValueType::Vector, "(0, 0, 0)", "Move."),
    },
    "",
    true,
};

KeySpec as_placement_step(KeySpec key) {
    key.placement_step = true;
    return key;
}

// The placement steps of a shape or a group: any number of each, applied in the order written.
std::vector<KeySpec> placement_step_keys() {
    return {
        as_placement_step(scale_key("Scale about the origin, uniform or per axis; a negative factor mirrors.")),
        as_placement_step(
            rotate_key("Rotate about an axis through the origin: `rotate { axis (x, y, z) angle degrees }`.")),
        as_placement_step(key("translate", ValueType::Vector, "(0, 0, 0)", "Move.")),
        as_placement_step(nested(key("transform", ValueType::Block, "{ }",
                                  "Its steps, in their order, at this place in the chain: "
                                  "`transform { translate (0, 1, 0) rotate { angle 45 } scale (-1, 1, 1) }`, or "
                                  "a name `let` gave to one."),
                              &kTransform)),
    };
}

// The keys that place a shape, after the shape's own keys and before its material.
std::vector<KeySpec> placed(std::vector<KeySpec> keys, std::vector<KeySpec> after = {}) {
    for (KeySpec& step : placement_step_keys()) keys.push_back(std::move(step));
    keys.insert(keys.end(), after.begin(), after.end());
    keys.push_back(key("material", ValueType::MaterialRef, "", "A material name or an inline material block."));
    return keys;
}

const BlockSpec kSphere{
    "sphere", false, true, Occurs::Any,
    "A sphere, placed like a mesh (by one scale factor on every axis: a sphere stays a sphere).",
    placed({
        key("center", ValueType::Vector, "", "Center."),
        ranged(key("radius", ValueType::Number, "", "Radius."), kSmallestSize, kInf),
    }),
    "sphere {\n  center (1, -0.5, 3)\n  radius 0.5\n  material { ka 0.1 kd (0, 0, 1) ks 1 n 10 }\n}\n",
};

KeySpec caps_key() {
    return key("caps", ValueType::Boolean, "true",
               "Close the ends with flat discs (a solid); `false` leaves them open (a tube).");
}

const BlockSpec kCylinder{
    "cylinder", false, true, Occurs::Any,
    "A round cylinder between two points, closed by its caps unless `caps false`; placed like a sphere "
    "(by one scale factor on every axis).",
    placed({
        key("base", ValueType::Vector, "", "Center of one end."),
        key("top", ValueType::Vector, "", "Center of the other end; must differ from `base`."),
        ranged(key("radius", ValueType::Number, "", "Radius."), kSmallestSize, kInf),
        caps_key(),
    }),
    "cylinder {\n  base (0, -1, 0)\n  top (0, 1, 0)\n  radius 0.5\n  material { ka 0.1 kd (0.8, 0.6, 0.2) }\n}\n",
};

const BlockSpec kCone{
    "cone", false, true, Occurs::Any,
    "A round cone between two points with a radius at each end (0 makes a point; equal radii a "
    "cylinder), closed by its caps unless `caps false`; placed like a sphere.",
    placed({
        key("base", ValueType::Vector, "", "Center of one end."),
        key("top", ValueType::Vector, "", "Center of the other end; must differ from `base`."),
        ranged(key("base_radius", ValueType::Number, "", "Radius at `base` (0: a point)."), 0, kInf),
        ranged(key("top_radius", ValueType::Number, "0", "Radius at `top` (0: a point)."), 0, kInf),
        caps_key(),
    }),
    "cone {\n  base (0, -1, 0)\n  top (0, 1, 0)\n  base_radius 0.7\n  material { ka 0.1 kd (0.9, 0.3, 0.2) }\n}\n",
};

const BlockSpec kDisc{
    "disc", false, true, Occurs::Any,
    "A flat round disc, seen from both sides; placed like a sphere.",
    placed({
        key("center", ValueType::Vector, "", "Center."),
        nonzero(key("normal", ValueType::Vector, "", "The disc's normal (normalised for you): its front.")),
        ranged(key("radius", ValueType::Number, "", "Radius."), kSmallestSize, kInf),
    }),
    "disc {\n  center (0, -1, 0)\n  normal (0, 1, 0)\n  radius 2\n  material { ka 0.1 kd 0.8 }\n}\n",
};

const BlockSpec kGroup{
    "group", false, false, Occurs::Any,
    "The placement of a `group { ... }`, written before its contents: its steps, in the order written, "
    "place every shape and light made inside, after their own placement (groups inside groups: the "
    "inner one first).",
    placement_step_keys(),
    "",
};

const BlockSpec kMesh{
    "mesh", false, true, Occurs::Any,
    "A triangle mesh from an OBJ file, placed by its steps (`scale`, `rotate`, `translate`, "
    "`transform`) in the order written.",
    placed({key("file", ValueType::Path, "",
                "The OBJ file, relative to the scene file's folder. Blocks naming the same file share "
                "it: it is read and its BVH built once.")},
           {one_of(key("shading", ValueType::Choice, "smooth",
                       "`smooth` interpolates vertex normals across each triangle (the file's `vn`, else "
                       "the area-weighted average of the faces at each vertex: a cube of 8 shared corners "
                       "looks like a cushion); `flat` gives each triangle its own normal (hard edges)."),
                   {"smooth", "flat"})}),
    "mesh {\n  file \"../scenes/meshes/tetrahedron.obj\"\n  scale 0.5\n"
    "  rotate { axis (0, 1, 0) angle 30 }\n  translate (0, -0.5, 0)\n  material { kd 0.8 }\n}\n",
};

const BlockSpec kTriangle{
    "triangle", false, true, Occurs::Any,
    "A flat triangle, seen from both sides, placed like a mesh.",
    placed({key("a", ValueType::Vector, "", "First corner."), key("b", ValueType::Vector, "", "Second corner."),
            key("c", ValueType::Vector, "", "Third corner; (b - a) x (c - a) is the front's normal.")}),
    "triangle {\n  a (-1, 0, 0)\n  b (1, 0, 0)\n  c (0, 1.5, 0)\n  material { kd (1, 0.5, 0) }\n}\n",
};

const BlockSpec kQuad{
    "quad", false, true, Occurs::Any,
    "A flat parallelogram (a rectangle when the edges are perpendicular), seen from both sides, "
    "placed like a mesh: its corners are `corner`, `corner + edge1`, `corner + edge1 + edge2` and "
    "`corner + edge2`.",
    placed({key("corner", ValueType::Vector, "", "One corner."),
            nonzero(key("edge1", ValueType::Vector, "", "The edge from `corner` to the next corner.")),
            nonzero(key("edge2", ValueType::Vector, "",
                        "The other edge from `corner`; edge1 x edge2 is the front's normal."))}),
    "quad {\n  corner (-2, 0, -2)\n  edge1 (0, 0, 4)\n  edge2 (4, 0, 0)\n  material { kd 0.8 km 0.2 }\n}\n",
};

const BlockSpec kBox{
    "box", false, true, Occurs::Any,
    "A box with flat faces, axis-aligned between two corners before it is placed like a mesh.",
    placed({key("min", ValueType::Vector, "", "The corner with the smallest x, y and z."),
            key("max", ValueType::Vector, "", "The opposite corner: larger on every axis.")}),
    "box {\n  min (-0.5, 0, -0.5)\n  max (0.5, 1, 0.5)\n  rotate { axis (0, 1, 0) angle 30 }\n"
    "  material { kd (0.2, 0.4, 0.9) }\n}\n",
};

// The patterns: values of a material's ka and kd (pattern.h has their definitions).
KeySpec mapping_key(std::string_view default_value) {
    return one_of(key("mapping", ValueType::Choice, default_value,
                      "How a point becomes the pattern's coordinates: `solid` the point itself (in the shape's "
                      "own coordinates, through the pattern's steps); `planar` its (x, y); `spherical` "
                      "(longitude, latitude) around the origin, each 0..1, u = 0.5 towards +z and rising towards "
                      "+x; `cylindrical` (longitude, y); `uv` the surface's own (u, v), not the point's."),
                  {"solid", "planar", "spherical", "cylindrical", "uv"});
}
KeySpec colors_key(std::string_view default_value) {
    return key("colors", ValueType::ColorMap, default_value,
               "The colour map: stops [value, colour] in order of value (0..1), linear between them; below "
               "the first stop its colour, above the last the last's.");
}
KeySpec axis_key(std::string_view default_value, std::string_view meaning) {
    return nonzero(key("axis", ValueType::Vector, default_value, meaning));
}
KeySpec octaves_key(std::string_view default_value) {
    return ranged(key("octaves", ValueType::Integer, default_value,
                      "Octaves of Perlin's turbulence: sum |noise(2^i p)| / 2^i for i below this."), 1, kMaxOctaves);
}
KeySpec turbulence_key(std::string_view default_value) {
    return ranged(key("turbulence", ValueType::Number, default_value,
                      "How far turbulence displaces the value (0: none)."), 0, kLargestMagnitude);
}

// A pattern's table: its own keys, then its mapping and its placement steps.
BlockSpec pattern(std::string_view kind, std::string_view summary, std::vector<KeySpec> keys,
                  std::string_view mapping_default, std::string_view example) {
    keys.push_back(mapping_key(mapping_default));
    keys.push_back(ranged(key("multiply", ValueType::Triple, "1",
                              "Every colour of the pattern times this, channel by channel: what `0.1 * pattern` "
                              "writes (an ambient term that follows the diffuse pattern: `ka 0.1 * floor`)."),
                          0, kInf));
    for (KeySpec& step : placement_step_keys()) keys.push_back(std::move(step));
    return BlockSpec{kind, false, false, Occurs::Any, summary, std::move(keys), example};
}

const BlockSpec kChecker = pattern("checker",
    "Cubes of side 1 in two colours (or two patterns): `even` where floor(x) + floor(y) + floor(z) "
    "is even, `odd` where it is odd, each coordinate nudged up by 1e-6 first so that a surface on a cell "
    "boundary (a floor at y = 0) takes the cell above it. With a 2D mapping, squares.",
    {ranged(key("even", ValueType::Paint, "1", "The colour (or pattern) of the even cells."), 0, kInf),
     ranged(key("odd", ValueType::Paint, "0", "The colour (or pattern) of the odd cells."), 0, kInf)},
    "solid", "plane {\n  point (0, -1, 0)\n  normal (0, 1, 0)\n  material { ka 0.1 kd checker { even 0.9 odd (0.8, 0.1, 0.1) scale 0.5 } }\n}\n");
const BlockSpec kStripes = pattern("stripes",
    "Bands across `axis`: the colour map stepped (no blending) at the fraction of the distance along it.",
    {colors_key("[[0, 1], [0.5, 0]]"), axis_key("(0, 1, 0)", "The direction across the bands.")},
    "solid", "sphere {\n  center (0, 0, 0)\n  radius 1\n  material { kd stripes { colors [[0, (1, 0, 0)], [0.5, 1]] axis (1, 0, 0) scale 0.2 } }\n}\n");
const BlockSpec kGradient = pattern("gradient",
    "The colour map along `axis`, blended, repeating every unit: the value is the fraction of p . axis.",
    {colors_key("[[0, 0], [1, 1]]"), axis_key("(0, 1, 0)", "The direction of the ramp.")},
    "solid", "sphere {\n  center (0, 0, 0)\n  radius 100\n  material { ka gradient { colors [[0, (0.2, 0.3, 0.8)], [1, 1]] scale 100 } }\n}\n");
const BlockSpec kRings = pattern("rings",
    "Rings around the line through the origin along `axis`: the fraction of the distance from it.",
    {colors_key("[[0, 1], [0.5, 0], [1, 1]]"), axis_key("(0, 1, 0)", "The line the rings are around.")},
    "solid", "disc {\n  center (0, 0, 0)\n  normal (0, 0, 1)\n  radius 1\n  material { kd rings { axis (0, 0, 1) scale 0.25 } }\n}\n");
const BlockSpec kSpots = pattern("spots",
    "Perlin's improved noise (2002) as the value: 0.5 + 0.5 noise(p), clamped to 0..1.",
    {colors_key("[[0, 0], [1, 1]]")}, "solid", "sphere {\n  center (0, 0, 0)\n  radius 1\n  material { kd spots { colors [[0.4, 0.1], [0.6, (0.9, 0.8, 0.2)]] scale 0.3 } }\n}\n");
const BlockSpec kTurbulence = pattern("turbulence",
    "Perlin's turbulence as the value, clamped to 0..1.",
    {colors_key("[[0, 0], [1, 1]]"), octaves_key("6")}, "solid", "sphere {\n  center (0, 0, 0)\n  radius 1\n  material { kd turbulence { octaves 4 scale 0.5 } }\n}\n");
const BlockSpec kMarble = pattern("marble",
    "Veins across `axis`: 0.5 + 0.5 sin(2 pi (p . axis + turbulence * turbulence(p, octaves))).",
    {colors_key("[[0, (0.9, 0.9, 0.85)], [0.7, (0.55, 0.55, 0.6)], [1, (0.2, 0.2, 0.3)]]"),
     axis_key("(1, 0, 0)", "The direction across the veins."), turbulence_key("1"), octaves_key("6")},
    "solid", "let stone = marble { turbulence 1.5 scale 0.5 }\nbox {\n  min (-1, -1, -1)\n  max (1, 1, 1)\n  material { ka 0.1 kd stone }\n}\n");
const BlockSpec kWood = pattern("wood",
    "Rings around `axis` disturbed by turbulence: the fraction of (distance from the axis + turbulence * "
    "turbulence(p, octaves)).",
    {colors_key("[[0, (0.85, 0.6, 0.35)], [0.6, (0.6, 0.35, 0.15)], [1, (0.85, 0.6, 0.35)]]"),
     axis_key("(0, 1, 0)", "The trunk's line."), turbulence_key("0.05"), octaves_key("4")},
    "solid", "cylinder {\n  base (0, 0, 0)\n  top (0, 2, 0)\n  radius 0.5\n  material { kd wood { scale 0.1 rotate { axis (1, 0, 0) angle 90 } } }\n}\n");
const BlockSpec kImage = pattern("image",
    "A picture read through OpenImageIO (PNG, JPEG, EXR, ...) over the square 0..1 of (u, v): u across, v up, "
    "bilinear between texel centers. 8-bit files are decoded from sRGB to linear; float files (EXR, HDR) are "
    "linear already.",
    {key("file", ValueType::Path, "", "The image file, relative to the scene file's folder."),
     one_of(key("wrap", ValueType::Choice, "repeat",
                "Outside 0..1: `repeat` tiles the picture, `clamp` extends its edge texels, `mirror` tiles it "
                "flipped every other time."),
            {"repeat", "clamp", "mirror"})},
    "planar", "quad {\n  corner (-1, -1, 0)\n  edge1 (2, 0, 0)\n  edge2 (0, 2, 0)\n  material { kd image { file \"../scenes/textures/uv_grid.png\" mapping uv } }\n}\n");

// Fading with distance, shared by the lights that have a position.
#define FADE_KEYS                                                                                                \
    ranged(key("fade_distance", ValueType::Number, "0",                                                          \
               "Fading: the colour times 2 / (1 + (d / fade_distance)^fade_power) at distance d (0: none)."), \
           0, kInf),                                                                                             \
        ranged(key("fade_power", ValueType::Number, "2", "Fading's exponent (with fade_distance)."), 0, 1000),

const BlockSpec kLight{
    "light", false, true, Occurs::Any,
    "A point light without fall-off.",
    {
        key("position", ValueType::Vector, "", "Position."),
        ranged(key("color", ValueType::Triple, "1", "Colour; multiplies diffuse and specular."), 0, kInf),
        FADE_KEYS
    },
    "light {\n  position (0, 3, -2)\n  color 0.2\n}\n",
};

const BlockSpec kSpotlight{
    "spotlight", false, true, Occurs::Any,
    "A point light shining in a cone (POV-Ray's spotlight): full within `radius` degrees of the axis from "
    "`position` to `point_at`, falling smoothly to nothing at `falloff` degrees, times cos(angle)^`tightness`.",
    {
        key("position", ValueType::Vector, "", "Position."),
        key("point_at", ValueType::Vector, "", "A point on the cone's axis (not the position)."),
        ranged(key("color", ValueType::Triple, "1", "Colour; multiplies diffuse and specular."), 0, kInf),
        ranged(key("radius", ValueType::Number, "30", "Half-angle of the full cone, in degrees."), 0, 90),
        ranged(key("falloff", ValueType::Number, "45",
                   "Half-angle where the light ends, in degrees (at least radius)."), 0, 90),
        ranged(key("tightness", ValueType::Number, "0",
                   "Exponent of cos(angle) over the whole cone (0: none)."), 0, 10000),
        FADE_KEYS
    },
    "spotlight {\n  position (0, 5, 0)\n  point_at (0, 0, 0)\n  radius 15\n  falloff 25\n}\n",
};

const BlockSpec kParallelLight{
    "parallel_light", false, true, Occurs::Any,
    "A light from infinitely far away (the sun): every point is lit along `direction`, the way its light "
    "travels, and shadowed by anything in the way.",
    {
        nonzero(key("direction", ValueType::Vector, "", "The way the light travels (from the light to the scene).")),
        ranged(key("color", ValueType::Triple, "1", "Colour; multiplies diffuse and specular."), 0, kInf),
    },
    "parallel_light {\n  direction (-1, -2, -1)\n  color 0.8\n}\n",
};

const BlockSpec kAreaLight{
    "area_light", false, true, Occurs::Any,
    "A rectangle of point lights (soft shadows): `samples1` x `samples2` of them on a grid centred on "
    "`position`, from corner to corner of the rectangle with edges `edge1` and `edge2` (POV-Ray's area_light), "
    "each with `color` / (samples1 x samples2) and its own shadow ray. One sample is a point light.",
    {
        key("position", ValueType::Vector, "", "The rectangle's centre."),
        ranged(key("color", ValueType::Triple, "1", "Colour of the whole light, shared by its samples."), 0, kInf),
        nonzero(key("edge1", ValueType::Vector, "", "One edge of the rectangle.")),
        nonzero(key("edge2", ValueType::Vector, "", "The other edge (not parallel to edge1).")),
        ranged(key("samples1", ValueType::Integer, "", "Samples along edge1 (its two ends included)."), 1, 256),
        ranged(key("samples2", ValueType::Integer, "", "Samples along edge2 (its two ends included)."), 1, 256),
        one_of(key("shape", ValueType::Choice, "rectangle",
                   "`rectangle`; `disc`, the ellipse inscribed in the rectangle (its samples the grid's, mapped "
                   "onto it); `sphere`, a ball of diameter |edge1| (edges of one length, as many samples along "
                   "each), seen from every point as the disc of its outline."),
               {"rectangle", "disc", "sphere"}),
        key("jitter", ValueType::Boolean, "false",
            "Each sample at random in its cell of the rectangle, multi-jittered (along each edge alone the samples "
            "fill its N x M strips one each), anew at every point shaded (soft noise for bands)."),
        key("adaptive", ValueType::Boolean, "false",
            "Corners first: a part of the light whose corner samples are blocked by one convex shape is taken "
            "as blocked, and one whose corners are lit as lit where every shape that may block it is wider than "
            "the gaps between them."),
        FADE_KEYS
    },
    "area_light {\n  position (0, 4, 0)\n  edge1 (1, 0, 0)\n  edge2 (0, 0, 1)\n  samples1 8\n  samples2 8\n}\n",
};
#undef FADE_KEYS
// clang-format on

}  // namespace

const KeySpec* BlockSpec::find_key(std::string_view key_name) const {
    for (const KeySpec& spec : keys)  // the first letters first: most keys differ there
        if (!key_name.empty() && spec.name[0] == key_name[0] && spec.name == key_name) return &spec;
    return nullptr;
}

const std::vector<const BlockSpec*>& all_block_specs() {
    static const std::vector<const BlockSpec*> specs{&kCamera, &kRender,    &kMaterial,  &kSphere,       &kPlane,
                                                     &kMesh,   &kTriangle,  &kQuad,      &kBox,          &kCylinder,
                                                     &kCone,   &kDisc,      &kRotate,    &kTransform,    &kGroup,
                                                     &kLight,  &kAreaLight, &kSpotlight, &kParallelLight};
    return specs;
}

const std::vector<const BlockSpec*>& pattern_specs() {
    static const std::vector<const BlockSpec*> specs{&kChecker,    &kStripes, &kGradient, &kRings, &kSpots,
                                                     &kTurbulence, &kMarble,  &kWood,     &kImage};
    return specs;
}

const BlockSpec* find_pattern_spec(std::string_view kind) {
    for (const BlockSpec* spec : pattern_specs())
        if (spec->kind == kind) return spec;
    return nullptr;
}

const BlockSpec& group_spec() {
    return kGroup;
}

const BlockSpec* find_block_spec(std::string_view kind) {
    for (const BlockSpec* spec : all_block_specs())
        if (spec->top_level && !kind.empty() && spec->kind[0] == kind[0] && spec->kind == kind) return spec;
    return nullptr;
}

std::string format_number(double value) {
    char buffer[32];
    // Whole numbers below 1e15 in plain digits; everything else in the shortest exact form.
    auto result = std::floor(value) == value && std::fabs(value) < 1e15
                      ? std::to_chars(buffer, buffer + sizeof buffer, (long long)value)
                      : shortest_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

std::string_view describe(ValueType type) {
    switch (type) {
        case ValueType::Number: return "a number";
        case ValueType::Integer: return "a whole number";
        case ValueType::Boolean: return "true or false";
        case ValueType::Vector: return "a vector (x, y, z)";
        case ValueType::Triple: return "a number or a vector (x, y, z)";
        case ValueType::Path: return "a file path in double quotes";
        case ValueType::MaterialRef: return "a material name or an inline material { ... }";
        case ValueType::Block: return "a block { ... }";
        case ValueType::Choice: return "a name";
        case ValueType::Paint: return "a colour (a number or (r, g, b)) or a pattern such as checker { ... }";
        case ValueType::ColorMap: return "a list of stops [value, colour]";
    }
    return "a value";
}

}  // namespace tracer
