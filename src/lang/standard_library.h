// The standard library: scene files shipped inside tracer (named colours and materials), found
// by `include "std/NAME.scn"` on every machine, in the browser and from Python alike, with no
// file to install. Their text is built into the program from src/lang/std/.
#pragma once

#include <span>
#include <string_view>

namespace tracer {

struct LibraryFile {
    std::string_view name;  // as included: "std/colors.scn"
    std::string_view text;
};

// Every file of the standard library, in name order.
std::span<const LibraryFile> standard_library();

// The file `name` ("std/colors.scn") of the standard library, or nullptr if it has none.
const LibraryFile* find_library_file(std::string_view name);

// Whether an include of `written` means the standard library: its path begins with "std/".
bool names_standard_library(std::string_view written);

// The path messages give a library file: "<std>/colors.scn" (no file on disk has it).
std::string_view library_display_prefix();

// Whether `path` (as messages give it) is a file of the standard library, not one on disk.
bool is_library_path(std::string_view path);

}  // namespace tracer
