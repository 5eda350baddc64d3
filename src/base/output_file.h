// Writing an output file so that it keeps its promise: the file at the path is either the old
// one, untouched, or the complete new one, never a truncated mix. The bytes go to a temporary
// file beside the target, every write checked to the last byte and flushed to disk (fsync),
// then renamed over it; on any failure the temporary file is removed.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace tracer {

// Writes `bytes` to `path` atomically; returns the reason on failure ("No space left on
// device", "permission denied") with `path` unchanged.
std::optional<std::string> write_file_atomically(const std::string& path, std::string_view bytes);

// Why nothing could be written at `path` (its folder is missing or not writable, it is a
// folder), or nullopt: checked before a long render, not after.
std::optional<std::string> output_path_problem(const std::string& path);

// True if the two paths name the same file (the same inode, or the same path once resolved
// when either does not exist yet).
bool same_file(const std::string& a, const std::string& b);

}  // namespace tracer
