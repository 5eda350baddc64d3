// Recursive-descent parser for the scene language (grammar/scene.ebnf). One function per
// grammar rule. On a syntax error it reports once, skips to the end of the enclosing
// top-level block and carries on, so one run reports the errors of several blocks.
#pragma once

#include "lang/ast.h"
#include "base/diagnostics.h"
#include "base/source.h"

namespace tracer {

// Parses a whole scene file; syntax errors go to `diagnostics`.
SceneAst parse_scene(const SourceFile& file, Diagnostics& diagnostics);

// Parses a single value (used for the defaults written in the block tables).
bool parse_single_value(const SourceFile& file, Diagnostics& diagnostics, Value& out);

}  // namespace tracer
