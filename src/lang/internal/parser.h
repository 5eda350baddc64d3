// Recursive-descent parser for the scene language (grammar/scene.ebnf). One function per
// grammar rule. On a syntax error it reports once, skips to the end of the enclosing
// top-level block and carries on, so one run reports the errors of several blocks.
#pragma once

#include <memory>
#include <vector>

#include "base/diagnostics.h"
#include "base/source.h"
#include "lang/internal/syntax_tree.h"

namespace tracer {

// Parses a whole scene file; syntax errors go to `diagnostics`. Spans carry `origin` (Sources).
Program parse_program(const SourceFile& file, Diagnostics& diagnostics, uint32_t origin = 0);

class Parser;
// Parses a file one top-level statement at a time, so that a big scene is run as it is read
// and never held whole.
class StatementReader {
public:
    StatementReader(const SourceFile& file, Diagnostics& diagnostics, uint32_t origin = 0);
    ~StatementReader();
    // Appends the next statement to `out` (nothing if it was too broken to keep); false at the
    // end of the file.
    bool next(std::vector<Statement>& out);

private:
    std::unique_ptr<Parser> parser_;
};

// Parses a single value: an expression or a block (the defaults written in the block tables,
// settings from the command line). False on a syntax error or text after the value.
bool parse_single_expression(const SourceFile& file, Diagnostics& diagnostics, Expr& out);

}  // namespace tracer
