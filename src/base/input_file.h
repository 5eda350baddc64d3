// Reading an input file (a scene, a mesh) whole, safely: only regular files, up to a size
// limit, so a FIFO, a device such as /dev/zero or a runaway file is refused at once with the
// reason instead of blocking or exhausting memory.
#pragma once

#include <cstdint>
#include <string>

namespace tracer {

// The largest scene file read (a million spheres is ~68 MB; memory grows ~16x the file).
inline constexpr uint64_t kMaxSceneFileBytes = uint64_t(128) << 20;
// The largest OBJ file read (~25 million triangles; memory grows ~8x the file size).
inline constexpr uint64_t kMaxMeshFileBytes = uint64_t(1) << 30;

struct InputFile {
    std::string text;
    std::string problem;  // empty when the file was read
};

// The whole text of `path`, or why it cannot be read ("No such file or directory", "it is a
// FIFO, not a regular file", "it is 2.1 GB; the limit is 1.0 GB"): never blocks on special files.
InputFile read_input_file(const std::string& path, uint64_t max_bytes);

// Standard input read to its end (waiting for the writer, as the user asked for it), or why
// not: an error, or more than max_bytes.
InputFile read_standard_input(uint64_t max_bytes);

// Why `path` could not be read as an input file, looking without opening it (so without
// blocking); empty if it looks readable. The same reasons as read_input_file gives.
std::string input_file_problem(const std::string& path, uint64_t max_bytes);

// strerror's text, lower-cased to read as the rest of a message ("no such file or directory").
std::string errno_text(int error);

// A byte count for messages: "312 bytes", "4.2 MB", "1.5 GB".
std::string describe_bytes(uint64_t bytes);

}  // namespace tracer
