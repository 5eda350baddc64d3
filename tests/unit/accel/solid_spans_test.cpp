// combine_spans (accel/solid_spans.h) against brute force: random solids along a line, each a
// list of spans with ends on a coarse grid (so that ends of the two solids often coincide),
// some nudged by less than the tolerance; the result must hold exactly the points that the
// operation's truth table says, away from the ends, and never a span between two ends that are
// one place.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "accel/solid_spans.h"

namespace tracer {
namespace {

constexpr Real kTolerance = 1e-9;

// True if `t` lies inside one of `spans` (an end counts as inside).
bool inside_spans(const std::vector<SolidSpan>& spans, Real t) {
    return std::any_of(spans.begin(), spans.end(),
                       [t](const SolidSpan& span) { return span.enter.t <= t && t <= span.leave.t; });
}

// Spans with ends on the integers 0..20 (surfaces numbered from `first_surface`), each end
// nudged by up to a tenth of the tolerance in one case of three.
std::vector<SolidSpan> random_solid(std::mt19937& random, uint32_t first_surface) {
    std::uniform_int_distribution<int> grid(0, 20), nudge(0, 2);
    std::vector<int> ends;
    for (int k = std::uniform_int_distribution<int>(0, 4)(random) * 2; k > 0; --k) ends.push_back(grid(random));
    std::sort(ends.begin(), ends.end());
    std::vector<SolidSpan> spans;
    for (size_t k = 0; k + 1 < ends.size(); k += 2) {
        if (!spans.empty() && spans.back().leave.t >= Real(ends[k])) continue;  // keep them disjoint
        auto end = [&](int at) { return Real(at) + (nudge(random) == 0 ? kTolerance / 10 : 0); };
        const Real enter = end(ends[k]), leave = std::max(enter, end(ends[k + 1]));  // a tangent: enter = leave
        spans.push_back({{enter, first_surface + uint32_t(k), false}, {leave, first_surface + uint32_t(k + 1), false}});
    }
    return spans;
}

// `a` op `b` as combine_spans gives it.
std::vector<SolidSpan> combined(SolidOp op, const std::vector<SolidSpan>& a, const std::vector<SolidSpan>& b) {
    std::vector<SolidSpan> out;
    combine_spans(op, a, b, kTolerance, out);
    return out;
}

bool truth(SolidOp op, bool a, bool b) {
    return op == SolidOp::Union ? a || b : op == SolidOp::Intersection ? a && b : a && !b;
}

TEST(SolidSpans, EachOperationHoldsWhatItsTruthTableSays) {
    std::mt19937 random(5);
    for (int trial = 0; trial < 20000; ++trial) {
        const std::vector<SolidSpan> a = random_solid(random, 0), b = random_solid(random, 100);
        for (const SolidOp op : {SolidOp::Union, SolidOp::Intersection, SolidOp::Difference}) {
            const std::vector<SolidSpan> out = combined(op, a, b);
            for (Real t = -0.5; t <= 20.5; t += 0.5) {
                if (t == std::floor(t)) continue;  // on the grid: an end may lie there
                ASSERT_EQ(inside_spans(out, t), truth(op, inside_spans(a, t), inside_spans(b, t)))
                    << "trial " << trial << " op " << int(op) << " t " << t;
            }
            for (size_t k = 0; k < out.size(); ++k) {
                // Between ends that are one place there is no span, and the spans are in order.
                ASSERT_GT(out[k].leave.t - out[k].enter.t, kTolerance / 2) << "trial " << trial;
                if (k > 0) {
                    ASSERT_GT(out[k].enter.t - out[k - 1].leave.t, kTolerance / 2) << "trial " << trial;
                }
                // A difference's ends from the cutter (b) are its surface turned; the others are not.
                for (const SpanEnd& end : {out[k].enter, out[k].leave})
                    ASSERT_EQ(end.turned, op == SolidOp::Difference && end.surface >= 100);
            }
        }
    }
}

TEST(SolidSpans, CoincidentFacesGiveTheFirstSolidsFaceOrNone) {
    const SolidSpan box{{0, 1, false}, {4, 2, false}};
    const SolidSpan cutter{{kTolerance / 3, 11, false}, {2, 12, false}};  // its front face on the box's
    std::vector<SolidSpan> out = combined(SolidOp::Difference, {box}, {cutter});
    ASSERT_EQ(out.size(), 1u);             // no sliver between the two front faces
    EXPECT_EQ(out[0].enter.surface, 12u);  // the cutter's back face, seen from inside it
    EXPECT_TRUE(out[0].enter.turned);
    EXPECT_EQ(out[0].leave.surface, 2u);
    // A union of two solids touching at one place is one span: no face inside (merge).
    out = combined(SolidOp::Union, {{{0, 1, false}, {1, 2, false}}}, {{{1, 3, false}, {2, 4, false}}});
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].enter.surface, 1u);
    EXPECT_EQ(out[0].leave.surface, 4u);
    // Two coincident fronts: the first solid's face.
    out = combined(SolidOp::Intersection, {{{0, 1, false}, {3, 2, false}}}, {{{0, 3, false}, {2, 4, false}}});
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].enter.surface, 1u);
    EXPECT_EQ(out[0].leave.surface, 4u);
}

TEST(SolidSpans, HalfSpacesAndNestingCombine) {
    // A half-space (a plane's inside) reaches -infinity; (a plane's inside) minus a span, then
    // intersected with a span: the ends of the nested result come from each level.
    const SolidSpan half{{-kInfinity, 1, false}, {5, 2, false}};
    const SolidSpan hole{{1, 3, false}, {2, 4, false}};
    const SolidSpan clip{{0, 5, false}, {10, 6, false}};
    const std::vector<SolidSpan> out =
        combined(SolidOp::Intersection, combined(SolidOp::Difference, {half}, {hole}), {clip});
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(out[0].enter.surface, 5u);
    EXPECT_EQ(out[0].leave.surface, 3u);
    EXPECT_TRUE(out[0].leave.turned);
    EXPECT_EQ(out[1].enter.surface, 4u);
    EXPECT_EQ(out[1].leave.surface, 2u);
}

}  // namespace
}  // namespace tracer
