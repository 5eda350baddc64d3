#include "base/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

namespace tracer {

std::string describe_bytes(uint64_t bytes) {
    char text[32];
    if (bytes < 1000)
        std::snprintf(text, sizeof text, "%llu bytes", static_cast<unsigned long long>(bytes));
    else if (bytes < 1000 * 1000 * 1000)
        std::snprintf(text, sizeof text, "%.1f MB", double(bytes) / 1e6);
    else
        std::snprintf(text, sizeof text, "%.1f GB", double(bytes) / 1e9);
    return text;
}

std::string errno_text(int error) {
    std::string text = std::strerror(error);
    if (!text.empty() && text[0] >= 'A' && text[0] <= 'Z') text[0] = char(text[0] - 'A' + 'a');
    return text;
}

static const char* kind_of(mode_t mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "a special file";
}

// The reason a file of this kind and size is refused; empty if it is fine.
static std::string refusal(const struct stat& info, uint64_t max_bytes) {
    if (!S_ISREG(info.st_mode)) return std::string("it is ") + kind_of(info.st_mode) + ", not a regular file";
    if (uint64_t(info.st_size) > max_bytes)
        return "it is " + describe_bytes(uint64_t(info.st_size)) + "; the limit is " + describe_bytes(max_bytes);
    return "";
}

std::string input_file_problem(const std::string& path, uint64_t max_bytes) {
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0) return errno_text(errno);
    std::string problem = refusal(info, max_bytes);
    if (problem.empty() && ::access(path.c_str(), R_OK) != 0) problem = errno_text(errno);
    return problem;
}

// Reads `fd` to its end into `text`, growing it from its current size as needed and stopping
// once more than max_bytes are in; returns the bytes read (a read error goes to `problem`).
static size_t read_to_end(int fd, uint64_t max_bytes, std::string& text, std::string& problem) {
    size_t filled = 0;
    for (;;) {
        if (filled == text.size()) {
            if (filled > max_bytes) break;
            text.resize(size_t(std::min<uint64_t>(max_bytes + 1, filled + 65536)));
        }
        const ssize_t got = ::read(fd, text.data() + filled, text.size() - filled);
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) {
            problem = errno_text(errno);
            break;
        }
        if (got == 0) break;
        filled += size_t(got);
    }
    return filled;
}

InputFile read_input_file(const std::string& path, uint64_t max_bytes) {
    InputFile result;
    // Step 1: open without blocking (a FIFO with no writer would wait for ever) and look at
    // what was opened, not at the path, so nothing can be swapped in between.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) {
        result.problem = errno_text(errno);
        return result;
    }
    struct stat info {};
    result.problem = ::fstat(fd, &info) != 0 ? errno_text(errno) : refusal(info, max_bytes);
    if (!result.problem.empty()) {
        ::close(fd);
        return result;
    }

    // Step 2: read to the end, stopping one byte past the limit if the file grows meanwhile.
    result.text.resize(size_t(info.st_size) + 1);
    const size_t filled = read_to_end(fd, max_bytes, result.text, result.problem);
    ::close(fd);
    if (result.problem.empty() && filled > max_bytes)
        result.problem = "it grew past the limit of " + describe_bytes(max_bytes) + " while being read";
    result.text.resize(result.problem.empty() ? filled : 0);
    return result;
}

InputFile read_standard_input(uint64_t max_bytes) {
    InputFile result;
    const size_t filled = read_to_end(STDIN_FILENO, max_bytes, result.text, result.problem);
    if (result.problem.empty() && filled > max_bytes)
        result.problem = "more than the limit of " + describe_bytes(max_bytes);
    result.text.resize(result.problem.empty() ? filled : 0);
    return result;
}

}  // namespace tracer
