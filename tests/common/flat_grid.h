// Test geometry shared by the unit tests and the hard cases.
#pragma once

#include <cstdint>

#include "scene/triangle_mesh.h"

namespace tracer {

// hard-cases.md A3: 64 x 64 unit squares in z = 0, each split along its diagonal from (i, j)
// to (i + 1, j + 1) (8,192 triangles): every BVH box has zero thickness.
inline TriangleMesh flat_grid() {
    TriangleMesh grid;
    for (int j = 0; j <= 64; ++j)
        for (int i = 0; i <= 64; ++i) grid.positions.push_back({double(i), double(j), 0.0});
    auto at = [](int i, int j) { return uint32_t(j * 65 + i); };
    for (int j = 0; j < 64; ++j)
        for (int i = 0; i < 64; ++i) {
            grid.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            grid.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return grid;
}

}  // namespace tracer
