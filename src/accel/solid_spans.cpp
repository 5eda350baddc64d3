#include "accel/solid_spans.h"

#include <algorithm>
#include <cstddef>
#include <utility>

namespace tracer {
namespace {

// A place where the ray enters or leaves one of the two solids.
struct Crossing {
    SpanEnd end;
    bool from_b;
    bool entering;
};

// The crossings of `a` and `b` in order along the ray (a's first where they are equal), in the
// thread's scratch (a ray allocates nothing once it has run).
const std::vector<Crossing>& merged_crossings(std::span<const SolidSpan> a, std::span<const SolidSpan> b) {
    thread_local std::vector<Crossing> crossings;
    crossings.clear();
    for (const auto& [spans, from_b] : {std::pair{a, false}, std::pair{b, true}})
        for (const SolidSpan& span : spans) {
            crossings.push_back({span.enter, from_b, true});
            crossings.push_back({span.leave, from_b, false});
        }
    // Each half is in order already; the merge is stable, so a's come first on a tie.
    std::inplace_merge(crossings.begin(), crossings.begin() + std::ptrdiff_t(2 * a.size()), crossings.end(),
                       [](const Crossing& x, const Crossing& y) { return x.end.t < y.end.t; });
    return crossings;
}

bool inside(SolidOp op, bool in_a, bool in_b) {
    switch (op) {
        case SolidOp::Union: return in_a || in_b;
        case SolidOp::Intersection: return in_a && in_b;
        case SolidOp::Difference: return in_a && !in_b;
    }
    return false;
}

}  // namespace

void combine_spans(SolidOp op, std::span<const SolidSpan> a, std::span<const SolidSpan> b, Real tolerance,
                   std::vector<SolidSpan>& out) {
    const std::vector<Crossing>& crossings = merged_crossings(a, b);
    bool in_a = false, in_b = false, in_result = false;
    SolidSpan open;
    // Crossings within `tolerance` of a group's first are one place; the result changes there
    // at most once, and takes its end from the first crossing of `a` in the group, else of `b`.
    for (size_t first = 0; first < crossings.size();) {
        const Crossing* chosen = nullptr;
        size_t past = first;
        // The first always (an infinite t is no distance from itself: inf - inf is NaN).
        for (;
             past < crossings.size() && (past == first || crossings[past].end.t - crossings[first].end.t <= tolerance);
             ++past) {
            const Crossing& c = crossings[past];
            (c.from_b ? in_b : in_a) = c.entering;
            if (!chosen || (chosen->from_b && !c.from_b)) chosen = &c;
        }
        first = past;
        const bool now = inside(op, in_a, in_b);
        if (now == in_result) continue;
        SpanEnd end = chosen->end;
        if (chosen->from_b && op == SolidOp::Difference) end.turned = !end.turned;
        in_result = now;
        if (now) {
            open.enter = end;
        } else {
            open.leave = end;
            out.push_back(open);
        }
    }
}

}  // namespace tracer
