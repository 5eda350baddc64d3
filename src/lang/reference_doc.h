// grammar/reference.md, generated from the block tables (`tracer --reference`), and the same
// tables as JSON for editors (`tracer --language-json`).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace tracer {

// The Markdown reference of every block and key: type, default, allowed range, meaning.
std::string reference_markdown();

// The block tables, statements, expression words and built-ins as JSON: what an editor needs to
// explain and complete a scene.
nlohmann::json language_json();

}  // namespace tracer
