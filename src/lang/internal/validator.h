// The validator's state and steps, shared by its two halves: validate.cpp (the table-driven
// checks, block by block, and the public entry points) and build_scene.cpp (the builders that
// turn checked fields into the scene description). Internal to lang/.
#pragma once

#include <filesystem>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/diagnostics.h"
#include "base/source.h"
#include "lang/internal/checked_fields.h"
#include "lang/internal/evaluated_scene.h"
#include "lang/schema.h"
#include "lang/validate.h"
#include "scene/placement.h"
#include "scene/scene.h"
#include "scene/triangle_mesh.h"

namespace tracer {

// Scales a vector to unit length without overflow or underflow; zero stays zero.
dvec3 normalized(dvec3 v);

class Validator {
public:
    Validator(const Sources& sources, Diagnostics& diagnostics, const ValidateOptions& options)
        : file_(sources), diagnostics_(diagnostics), options_(options) {
        std::error_code ignored;
        const std::filesystem::path scene_file(sources.scene().path());
        scene_.source_path = std::filesystem::absolute(scene_file, ignored).lexically_normal().string();
    }

    void set_parameters(const std::vector<std::pair<std::string, PlainValue>>& parameters);
    // Checks and builds one block; true if it kept any of the block's spans for later.
    bool accept(const Block& block);
    std::optional<SceneDescription> finish();
    // Checks one value of `key` as a scene's block would (its type, range and other rules).
    bool check_setting(const PlainValue& value, const KeySpec& key, const BlockSpec& spec) {
        Fields fields(spec);
        fields.set(key, value, value.span);
        return check_value(value, key, fields);
    }

private:
    void check_and_build(const Block& block);
    // Generic checks driven by the tables.
    bool check_block_header(const Block& block, const BlockSpec& spec);
    bool check_body(const Body& body, const BlockSpec& spec, Span owner, Fields& fields);
    bool check_steps(const Body& body, const BlockSpec& spec, Fields& fields);
    bool unknown_key(const Entry& entry, const BlockSpec& spec, std::vector<std::string>& suggested);
    bool check_value(const PlainValue& value, const KeySpec& key, Fields& fields);
    bool check_number(double number, Span span, const KeySpec& key);
    bool check_perfect_square(double number, Span span, const KeySpec& key);
    bool check_power_of_two(double number, Span span, const KeySpec& key);
    bool type_error(const PlainValue& value, const KeySpec& key, const std::string& extra = "");

    // Builders: checked fields -> scene description.
    void add_named_material(const Block& block);
    int material_index(const Fields& fields);
    bool check_material_name(const PlainValue& value);
    Material build_material(const Fields& fields, std::string name);
    void build(const Block& block, const Fields& fields);
    void build_render(const Block& block, const Fields& fields);
    void build_camera(const Block& block, const Fields& fields);
    bool build_placed(const Block& block, const Fields& fields, Placed& out);
    bool build_placement(const Fields& fields, Placed& out);
    // Appends to `out` the steps of the groups `block` was made in, innermost first; false if a
    // group's placement is refused (reported once, at the group).
    bool add_group_steps(const Block& block, Placed& out);
    // The placement of a round shape (sphere, cylinder, cone, disc): false if refused (reported),
    // else `out` and its one scale factor `size`; the identity when nothing places the block.
    bool place_round(const Block& block, const Fields& fields, std::string_view what, Placement& out, double& size);
    bool check_round_reach(const Block& block, std::string_view what, std::initializer_list<dvec3> points,
                           double radius);
    void build_sphere(const Block& block, const Fields& fields);
    void build_cone(const Block& block, const Fields& fields);
    void build_disc(const Block& block, const Fields& fields);
    void build_plane(const Block& block, const Fields& fields);
    void build_mesh(const Block& block, const Fields& fields);
    void build_flat_shape(const Block& block, const Fields& fields);
    bool check_reach(const Block& block, const Placed& placed, const TriangleMesh& mesh);
    void warn_about_the_picture();

    const Sources& file_;  // the scene file and those it includes
    Diagnostics& diagnostics_;
    ValidateOptions options_;
    SceneDescription scene_;

    struct NamedMaterial {
        int index = -1;  // -1: the material's own block had errors
        Span name_span;
        bool used = false;
    };
    std::map<std::string, NamedMaterial, std::less<>> named_;
    // Material values shared by several shapes, by their body (held, so that no other body can
    // take its address): each made into one material.
    struct SharedMaterial {
        std::shared_ptr<const Body> body;
        int index;
    };
    std::map<const Body*, SharedMaterial> value_materials_;
    std::map<const BlockSpec*, Span> first_of_kind_;  // each kind's first block, by its table
    bool kept_ = false;  // the block being accepted had a span of its kept (in the members above or below)
    // Each group's own steps, by the group (held, so that no other group can take its address);
    // `ok` false if its placement was refused.
    struct GroupSteps {
        std::shared_ptr<const Group> group;
        bool ok = false;
        std::vector<TransformStep> steps;
    };
    std::map<const Group*, GroupSteps> group_steps_;
    // Materials used by name before their block, resolved by finish(): a shape's material index
    // kLaterMaterial - i stands for later_uses_[i].
    struct LaterUse {
        std::string name;
        Span span;
    };
    static constexpr int kLaterMaterial = -2;
    std::vector<LaterUse> later_uses_;
    void resolve_later_materials();
};

}  // namespace tracer
