// The validated scene description: what the front end hands to the renderer, to the JSON dump
// and (through the JSON) to the Mitsuba converter. Every default is filled in, materials are
// resolved to indices, paths are absolute and every value is in its documented range.
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>
#include "base/diagnostics.h"
#include "scene/pattern.h"

namespace tracer {

using dvec3 = glm::dvec3;

// Every number in a scene (and every coordinate of its mesh files) lies within
// +-kLargestMagnitude, and every size (radius, scale) is at least kSmallestSize: the renderer
// keeps bounding boxes in float (which ends at 3.4e38) and squares and cubes lengths (the
// watertight triangle test's error bound); this is the range it is tested over
// (docs/robustness.md).
constexpr double kLargestMagnitude = 1e30;
constexpr double kSmallestSize = 1e-30;

struct Material {
    std::string name;  // empty for a material written inline in a shape
    dvec3 ka{0.0};     // ambient, added once, never shadowed
    dvec3 kd{0.0};     // diffuse
    dvec3 ks{0.0};     // specular
    dvec3 km{0.0};     // mirror reflection
    double n = 1.0;    // specular (Phong) exponent
    dvec3 kt{0.0};     // transmission (refraction)
    double ior = 1.0;  // index of refraction of the inside (the side the normal points away from)
    // Patterns (pattern.h) in place of ka and kd, indices into SceneDescription::patterns (-1:
    // the colour), evaluated at the hit carried into the shape's own coordinates by `to_object`.
    int ka_pattern = -1;
    int kd_pattern = -1;
    Affine to_object;  // world -> the shape's own coordinates (a copy of the material per placement)

    bool patterned() const { return ka_pattern >= 0 || kd_pattern >= 0; }
};

struct Camera {
    dvec3 eye{0.0};
    dvec3 lookat{0.0, 0.0, -1.0};
    dvec3 up{0.0, 1.0, 0.0};
    double fovy_degrees = 45.0;  // vertical field of view
    double focal = 1.0;          // distance to the image plane (cancels out of the image)
};

// Which secondary rays a hit spawns (docs/spd.md): tracer's own rules, or those of the Standard
// Procedural Databases' testing procedure (its rules 8 and 10), for comparing ray counts.
enum class SpawnRules { Tracer, Spd };

// How a pixel's samples are placed: N x N in every pixel (uniform), or at the corners of cells
// split where they differ (adaptive; render/adaptive.h).
enum class Antialias { Uniform, Adaptive };

// How 8-bit image files hold the computed values: as they are (linear: round(255 v), Figure 1's
// rule), or encoded by the sRGB curve (IEC 61966-2-1) and marked so, as viewers expect. Float
// files (EXR, HDR, PFM) are linear either way.
enum class Encoding { Linear, Srgb };

// How rays find triangles: every triangle (none), one bounding box around the mesh (box),
// or a bounding volume hierarchy built by median splits (median) or the SAH (sah).
enum class Accelerator { None, Box, Median, Sah };

// The scene-language word of each setting's value ("sah", "spd", "adaptive": the render block's
// choices, one table each in scene.cpp), and back (false if unknown).
const char* accelerator_name(Accelerator accelerator);
bool accelerator_from_name(std::string_view name, Accelerator& out);
const char* spawn_rules_name(SpawnRules rules);
bool spawn_rules_from_name(std::string_view name, SpawnRules& out);
const char* antialias_name(Antialias antialias);
bool antialias_from_name(std::string_view name, Antialias& out);
const char* encoding_name(Encoding encoding);
bool encoding_from_name(std::string_view name, Encoding& out);

struct RenderSettings {
    int width = 1200;
    int height = 800;
    int max_depth = 4;      // reflection bounces after the primary hit
    int samples = 1;        // samples per pixel, a perfect square (N x N stratified)
    dvec3 background{0.0};  // colour of rays that leave the scene
    bool shadows = true;    // trace shadow rays to the lights
    // Shadow rays pass through transmitting surfaces, the light times kt at each one crossed
    // (not refracted); false: every surface blocks light.
    bool transparent_shadows = false;
    SpawnRules spawn_rules = SpawnRules::Tracer;
    Antialias antialias = Antialias::Uniform;
    double adaptive_threshold = 0.05;  // a cell is split where a channel of its corners differs by this much
    int adaptive_depth = 3;            // the most times a pixel is split (into 2^depth x 2^depth cells)
    double adaptive_cell = 1;          // the side of the first cells, in pixels: a power of two, 2^-depth .. 16
    Accelerator accel = Accelerator::Sah;
    int leaf_size = 4;                     // most triangles in a BVH leaf (median; sah may make smaller leaves)
    Encoding encoding = Encoding::Linear;  // of 8-bit image files
};

// The largest image, in pixels (8192 x 8192: 1.6 GB of pixel data in double precision).
constexpr long long kMaxPixels = 8192LL * 8192LL;

// Why these settings cannot be rendered (an image beyond kMaxPixels), or empty: the one rule
// for settings from a scene and from the command line alike.
std::string render_settings_problem(const RenderSettings& render);

struct Sphere {
    dvec3 center{0.0};
    double radius = 1.0;
    int material = 0;  // index into SceneDescription::materials
};

struct Plane {
    dvec3 point{0.0};
    dvec3 normal{0.0, 1.0, 0.0};  // unit length
    int material = 0;
};

// A cone with two radii, from the disc of `base_radius` around `base` to the disc of
// `top_radius` around `top` (a cylinder when they are equal; a pointed cone when one is 0), open
// or closed by those discs (`caps`). Curved normals on its side, flat ones on its caps; the
// normals point outwards, away from the axis. In world coordinates: the language places it.
struct Cone {
    dvec3 base{0.0}, top{0.0, 1.0, 0.0};
    double base_radius = 1.0, top_radius = 0.0;
    bool caps = true;
    int material = 0;
};

// A flat round disc, seen from both sides, in world coordinates.
struct Disc {
    dvec3 center{0.0};
    dvec3 normal{0.0, 1.0, 0.0};  // unit length: the front
    double radius = 1.0;
    int material = 0;
};

// A light: a point (`light`), a rectangle of point lights (`area_light`), a spotlight or a
// parallel light (docs/guide/lights.md). An area light is samples1 x samples2 point lights on a
// grid centred on `position`, spanning edge1 and edge2 corner to corner (POV-Ray's area_light),
// each with color / (samples1 samples2); the others have no edges and one sample.
struct Light {
    enum class Kind : uint8_t { Point, Spot, Parallel };  // an area light is a Point of many samples
    dvec3 position{0.0};
    dvec3 color{1.0};
    dvec3 edge1{0.0}, edge2{0.0};
    int samples1 = 1, samples2 = 1;
    // An area light's sampling: each sample moved at random inside its cell of the rectangle, a
    // seed per shaded point (jitter); corners first, a region taken as its corners say where they
    // agree (adaptive). Neither: the grid, every sample traced.
    bool jitter = false, adaptive = false;
    // An area light's shape: the rectangle; the disc (an ellipse) inscribed in it, the square of
    // samples mapped onto it by Shirley and Chiu's concentric map; or a sphere of diameter |edge1|,
    // seen from each point as the disc of its outline facing it (POV-Ray's `circular orient`).
    enum class Shape : uint8_t { Rectangle, Disc, Sphere };
    Shape shape = Shape::Rectangle;
    Kind kind = Kind::Point;
    // Spot: the cone's axis, from `position` towards `point_at`; parallel: the way its light
    // travels. Unit length (0 for the others).
    dvec3 direction{0.0};
    // A spotlight (POV-Ray's formula): full inside `radius` degrees of its axis, falling off by
    // a smooth step to nothing at `falloff` degrees, all of it times cos(angle)^tightness.
    double radius = 30, falloff = 45, tightness = 0;
    // Fading with distance d (POV-Ray's): the colour times 2 / (1 + (d / fade_distance)^fade_power);
    // 0: none (not for parallel lights, which have no position).
    double fade_distance = 0, fade_power = 2;

    int samples() const { return samples1 * samples2; }
    // Sample (i, j), 0 <= i < samples1, 0 <= j < samples2: `position` moved along each edge by
    // i / (samples1 - 1) - 1/2 of it (0 for one sample).
    dvec3 sample(int i, int j) const {
        const double a = samples1 > 1 ? double(i) / (samples1 - 1) - 0.5 : 0.0;
        const double b = samples2 > 1 ? double(j) / (samples2 - 1) - 0.5 : 0.0;
        return position + a * edge1 + b * edge2;
    }
    // True if the light's colour depends on where it shines (a spotlight's cone, fading).
    bool attenuates() const { return kind == Kind::Spot || fade_distance > 0; }
};

// One step of a transform block: scale by per-axis factors (negative ones mirror), rotate by
// `degrees` counter-clockwise looking down the unit axis `vector`, or translate by `vector`.
struct TransformStep {
    enum class Kind { Scale, Rotate, Translate };
    Kind kind = Kind::Translate;
    dvec3 vector{0.0};
    double degrees = 0.0;
};

// Where a shape's own coordinates go in the world: scale, then rotate about the axis, then
// translate, then the steps in order (a chain the block wrote in another order, and its groups').
struct Placed {
    dvec3 scale{1.0};                  // a negative factor mirrors
    dvec3 rotate_axis{0.0, 1.0, 0.0};  // unit length
    double rotate_degrees = 0.0;
    dvec3 translate{0.0};
    std::vector<TransformStep> steps;
    int material = 0;  // index into SceneDescription::materials
    int line = 0;      // the line of the block's first word, for statistics (0: not from a file)
};

// The whole placement as steps: scale, rotate and translate where they do anything, then the steps.
inline std::vector<TransformStep> placement_steps(const Placed& placed) {
    std::vector<TransformStep> steps;
    if (placed.scale != dvec3(1.0)) steps.push_back({TransformStep::Kind::Scale, placed.scale, 0});
    if (placed.rotate_degrees != 0)
        steps.push_back({TransformStep::Kind::Rotate, placed.rotate_axis, placed.rotate_degrees});
    if (placed.translate != dvec3(0.0)) steps.push_back({TransformStep::Kind::Translate, placed.translate, 0});
    steps.insert(steps.end(), placed.steps.begin(), placed.steps.end());
    return steps;
}

// A triangle mesh from an OBJ file.
struct Mesh : Placed {
    std::string path;   // absolute
    Location named_at;  // the `file` value in the scene, for messages about the OBJ file
    bool flat = false;  // shading: each triangle's own normal instead of interpolated vertex normals
};

// The finite flat shapes, flat-shaded and seen from both sides; their corners are in their own
// coordinates, before placing. A triangle's front is where (b - a) x (c - a) points.
struct FlatTriangle : Placed {
    dvec3 a{0.0}, b{0.0}, c{0.0};
};

// A parallelogram: corner, corner + edge1, corner + edge1 + edge2, corner + edge2. Its front is
// where edge1 x edge2 points.
struct Quad : Placed {
    dvec3 corner{0.0}, edge1{1.0, 0.0, 0.0}, edge2{0.0, 1.0, 0.0};
};

// An axis-aligned box (before placing) between two opposite corners, faces turned outwards.
struct Box : Placed {
    dvec3 min{0.0}, max{1.0};
};

// Solid modelling (CSG; docs/guide/solids.md): the union, intersection or difference of closed
// solids. A union (`merge` in POV-Ray's words) is one solid: the faces of a part inside another
// part vanish. A difference is its first part minus all the others.
enum class SolidOp : uint8_t { Union, Intersection, Difference };

// One part of a solid: a closed shape (an entry of one of SceneDescription's solid_* lists, in
// world coordinates; a mesh's file checked closed when read) or another solid (an entry of
// SceneDescription::solids).
struct SolidPart {
    enum class Kind : uint8_t { Sphere, Box, Cone, HalfSpace, Mesh, Solid };
    Kind kind = Kind::Sphere;
    uint32_t index = 0;
};

struct Solid {
    SolidOp op = SolidOp::Union;
    std::vector<SolidPart> parts;  // in the order written: a difference's first part is the one cut
    bool nested = false;           // a part of another solid (else an object of the world by itself)
    int line = 0;                  // the line of its keyword, for statistics
};

// A `param` of the scene and the value it took (from the command line, or its default): one
// number or a vector's components.
struct Parameter {
    std::string name;
    std::vector<double> value;
    bool vector = false;
};

struct SceneDescription {
    std::string source_path;                  // absolute path of the scene file
    std::vector<std::string> included_paths;  // every file the scene included, each once, as opened
    std::vector<Parameter> parameters;
    RenderSettings render;
    Camera camera;
    std::vector<Material> materials;
    std::vector<Sphere> spheres;
    std::vector<Plane> planes;
    std::vector<Mesh> meshes;
    std::vector<FlatTriangle> triangles;
    std::vector<Quad> quads;
    std::vector<Box> boxes;
    std::vector<Cone> cones;
    std::vector<Disc> discs;
    // Solids (CSG) and their shapes, apart from the shapes above: a plane there is a half-space
    // (the side its normal points away from), a cone always has caps.
    std::vector<Solid> solids;
    std::vector<Sphere> solid_spheres;
    std::vector<Box> solid_boxes;
    std::vector<Cone> solid_cones;
    std::vector<Plane> half_spaces;
    std::vector<Mesh> solid_meshes;
    std::vector<Light> lights;
    std::vector<Pattern> patterns;  // of the materials (pattern.h)
    std::vector<ImageFile> images;  // that image patterns read
};

}  // namespace tracer
