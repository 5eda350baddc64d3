// Solids (CSG): the blocks made inside union, merge, intersection and difference become the
// parts of a solid (scene.h's Solid) instead of shapes of their own. A union outside every other
// solid is a group: its shapes stay shapes, each with all its faces (POV-Ray's union); inside
// another solid, and as merge, it is one solid whose inner faces vanish.
#include <string>
#include <vector>

#include "lang/internal/scene_assembly.h"

namespace tracer {
namespace {

SolidOp solid_op(std::string_view keyword) {
    if (keyword == "intersection") return SolidOp::Intersection;
    if (keyword == "difference") return SolidOp::Difference;
    return SolidOp::Union;
}

// The blocks a solid may hold: closed shapes (material blocks define names, wherever written).
bool can_be_a_part(std::string_view kind) {
    return kind == "sphere" || kind == "box" || kind == "cylinder" || kind == "cone" || kind == "plane" ||
           kind == "mesh" || kind == "material";
}

// "a difference", "an intersection".
std::string with_article(const std::string& word) {
    return (word.find_first_of("aeiou") == 0 ? "an " : "a ") + word;
}

}  // namespace

int solid_of(SceneAssembly& a, const Block& block) {
    // Step 1: the solids' blocks around `block` not met before, innermost first, up to the first
    // one met before (whose solid is known).
    std::vector<const Group*> unknown;
    int solid = kNoSolid;
    for (const Group* group = block.group.get(); group; group = group->outer.get()) {
        if (group->kind == "group") continue;
        if (auto known = a.solids.find(group); known != a.solids.end()) {
            solid = known->second.index;
            break;
        }
        unknown.push_back(group);
    }
    // Step 2: each of them made, outermost first, a part of the solid around it.
    for (auto group = unknown.rbegin(); group != unknown.rend(); ++group) {
        if ((*group)->kind != "union" || solid != kNoSolid) {
            Solid made;
            made.op = solid_op((*group)->kind);
            made.nested = solid != kNoSolid;
            made.line = Diagnostics::locate(a.file, (*group)->keyword).line;
            const int index = int(a.scene.solids.size());
            a.scene.solids.push_back(std::move(made));
            if (solid != kNoSolid)
                a.scene.solids[size_t(solid)].parts.push_back({SolidPart::Kind::Solid, uint32_t(index)});
            solid = index;
        }
        a.solids[*group] = {block.group, solid};  // the innermost group holds those around it
        a.kept = true;
    }
    return solid;
}

void add_solid_part(SceneAssembly& a, int solid, SolidPart::Kind kind, size_t index) {
    a.scene.solids[size_t(solid)].parts.push_back({kind, uint32_t(index)});
}

bool check_solid_part(SceneAssembly& a, const Block& block) {
    if (can_be_a_part(block.kind)) return true;
    const int solid = solid_of(a, block);
    if (solid == kNoSolid) return true;
    const Group* around = block.group.get();
    while (around->kind == "group") around = around->outer.get();
    const std::string closed =
        "its parts are closed shapes (sphere, box, cylinder, cone, a closed mesh, a plane's half-space) "
        "and other solids";
    const std::string named = with_article(around->kind);
    Diagnostic* d = a.diagnostics.error(
        a.file, block.kind_span,
        block.kind.ends_with("light")  // light, area_light, spotlight, parallel_light
            ? "a light cannot be part of " + named + ": write it outside the " + around->kind
            : "a " + block.kind + " cannot be part of " + named + ", which needs an inside: " + closed);
    Diagnostics::note(d, a.file, around->keyword, "the " + around->kind + " is here");
    return false;
}

}  // namespace tracer
