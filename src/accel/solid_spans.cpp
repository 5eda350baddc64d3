#include "accel/solid_spans.h"

namespace tracer {
namespace {

// A place where the ray enters or leaves one of the two solids.
struct Crossing {
    SpanEnd end;
    bool from_b;
    bool entering;
};

// The crossings of `a` and `b` in order along the ray (a's first where they are equal).
std::vector<Crossing> merged_crossings(std::span<const Span> a, std::span<const Span> b) {
    std::vector<Crossing> crossings;
    crossings.reserve(2 * (a.size() + b.size()));
    size_t i = 0, j = 0;
    auto push = [&](const Span& span, bool from_b, bool leave) {
        crossings.push_back({leave ? span.leave : span.enter, from_b, !leave});
    };
    // Each list is walked end by end: 2 k is span k's enter, 2 k + 1 its leave.
    while (i < 2 * a.size() || j < 2 * b.size()) {
        const bool take_a =
            j >= 2 * b.size() || (i < 2 * a.size() && (i % 2 ? a[i / 2].leave.t : a[i / 2].enter.t) <=
                                                          (j % 2 ? b[j / 2].leave.t : b[j / 2].enter.t));
        if (take_a) {
            push(a[i / 2], false, i % 2), ++i;
        } else {
            push(b[j / 2], true, j % 2), ++j;
        }
    }
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

void combine_spans(SolidOp op, std::span<const Span> a, std::span<const Span> b, Real tolerance,
                   std::vector<Span>& out) {
    const std::vector<Crossing> crossings = merged_crossings(a, b);
    bool in_a = false, in_b = false, in_result = false;
    Span open;
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
