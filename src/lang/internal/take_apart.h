// Destroying a tree iteratively: a chain a + b + ... of a million terms is a million levels
// deep, too deep for a recursive destruction. Used by the syntax tree's and the code's nodes.
#pragma once

#include <utility>
#include <vector>

namespace tracer {

// Takes the subtrees under `operands` apart one node at a time (T has a vector `operands`).
template <class T>
void take_apart(std::vector<T>& operands) {
    if (operands.empty()) return;
    std::vector<T> pending = std::move(operands);
    while (!pending.empty()) {
        T last = std::move(pending.back());
        pending.pop_back();
        for (T& operand : last.operands) pending.push_back(std::move(operand));
        last.operands.clear();  // moved-from shells: their destruction goes no deeper
    }
}

}  // namespace tracer
