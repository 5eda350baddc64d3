#include "lang/standard_library.h"

#include <algorithm>
#include <cstddef>

namespace tracer {

// Generated at build time (src/lang/std/embed.cmake), sorted by name.
extern const LibraryFile kLibraryFiles[];
extern const size_t kLibraryFileCount;

std::span<const LibraryFile> standard_library() {
    return {kLibraryFiles, kLibraryFileCount};
}

const LibraryFile* find_library_file(std::string_view name) {
    const auto files = standard_library();
    const auto found = std::find_if(files.begin(), files.end(), [&](const LibraryFile& f) { return f.name == name; });
    return found == files.end() ? nullptr : &*found;
}

bool names_standard_library(std::string_view written) {
    return written.starts_with("std/");
}

std::string_view library_display_prefix() {
    return "<std>/";
}

bool is_library_path(std::string_view path) {
    return path.starts_with(library_display_prefix());
}

}  // namespace tracer
