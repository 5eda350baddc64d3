// Solid modelling along one ray (Roth, "Ray casting for modeling solids", 1982): a closed solid
// meets the ray's line in spans [enter, leave], sorted and disjoint; the union, intersection and
// difference of two solids combine their spans in one sweep, so a tree of them (CSG, issue 55)
// is classified bottom-up. Each end keeps the surface that made it (a leaf of the tree) and
// whether that surface is seen from its inside (a difference's cut face is the cutter's surface,
// turned). Spans cover the whole line, behind the origin too, so that a ray starting inside a
// solid needs no separate state: its first hit is the first end past its range's start.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "accel/types.h"
#include "scene/scene.h"

namespace tracer {

// One end of a span: where along the ray, and the surface there.
struct SpanEnd {
    Real t = 0;
    uint32_t surface = 0;  // the leaf whose surface bounds the span here
    bool turned = false;   // the surface seen from its inside (its normal turned)
    uint8_t part = 0;      // which face of the leaf: a box's 2 axis + (1 on the upper side)
};

// A stretch of the ray inside a solid.
struct SolidSpan {
    SpanEnd enter;
    SpanEnd leave;
};

// `a` op `b` appended to `out`, sorted and disjoint. Crossings of `a` and `b` within `tolerance`
// of each other (their error bounds) count as one place, where the result changes at most once
// and takes the first solid's (`a`'s) end if it has one there: two children's coincident faces
// make one face, or none, never the speckles of a coin toss, nor a sliver between them. A
// difference's ends taken from `b` are turned.
void combine_spans(SolidOp op, std::span<const SolidSpan> a, std::span<const SolidSpan> b, Real tolerance,
                   std::vector<SolidSpan>& out);

}  // namespace tracer
