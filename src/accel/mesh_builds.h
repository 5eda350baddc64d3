// Mesh BVHs held by a World, each possibly shared with other Worlds: the frames of an animation
// build a mesh file once (MeshBuildCache) and only their top levels again.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <tuple>
#include <utility>
#include <vector>

#include "accel/mesh_accel.h"
#include "scene/triangle_mesh.h"

namespace tracer {

// A World's meshes, indexed as a vector of MeshAccel is.
class MeshList {
public:
    const MeshAccel& operator[](size_t index) const { return *meshes_[index]; }
    const MeshAccel& back() const { return *meshes_.back(); }
    size_t size() const { return meshes_.size(); }
    bool empty() const { return meshes_.empty(); }
    // Iterates over the meshes themselves (not their pointers).
    struct Iterator {
        std::vector<std::shared_ptr<const MeshAccel>>::const_iterator at;
        const MeshAccel& operator*() const { return **at; }
        Iterator& operator++() { return ++at, *this; }
        bool operator!=(const Iterator& other) const { return at != other.at; }
    };
    Iterator begin() const { return {meshes_.begin()}; }
    Iterator end() const { return {meshes_.end()}; }
    // Builds a mesh of this World alone from MeshAccel's arguments.
    template <typename... Arguments>
    void emplace_back(Arguments&&... arguments) {
        meshes_.push_back(std::make_shared<const MeshAccel>(std::forward<Arguments>(arguments)...));
    }
    // Adds a mesh built elsewhere (and kept there too).
    void push_back(std::shared_ptr<const MeshAccel> mesh) { meshes_.push_back(std::move(mesh)); }

private:
    std::vector<std::shared_ptr<const MeshAccel>> meshes_;
};

// Mesh files built in their own coordinates, kept from one World to the next: a file is built
// again only when its mesh (a new read) or the build's settings differ.
class MeshBuildCache {
public:
    // The BVH of `file` (flat-shaded or not) under `settings`: the one built before, or a new one.
    std::shared_ptr<const MeshAccel> get(const SharedMesh& file, bool flat, const SearchSettings& settings) {
        const Key key{file.get(), flat, settings.brute_force, settings.build, settings.leaf_size, settings.keep_uvs};
        auto [known, is_new] = built_.try_emplace(key);
        if (is_new) {
            known->second = {file, std::make_shared<const MeshAccel>(*file, Placement(), settings, flat)};
            ++builds_;
        }
        return known->second.second;
    }
    // How many BVHs it built (for --stats-json: an animation's meshes are built once).
    size_t builds() const { return builds_; }

private:
    using Key = std::tuple<const TriangleMesh*, bool, bool, BvhBuild, int, bool>;
    std::map<Key, std::pair<SharedMesh, std::shared_ptr<const MeshAccel>>>
        built_;  // the file kept: its key stays its own
    size_t builds_ = 0;
};

}  // namespace tracer
