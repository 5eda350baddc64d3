// grammar/reference.md, generated from the block tables (`tracer --reference`).
#pragma once

#include <string>

namespace tracer {

// The Markdown reference of every block and key: type, default, allowed range, meaning.
std::string reference_markdown();

}  // namespace tracer
