#include "base/output_file.h"

#include "base/input_file.h"  // errno_text

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace tracer {
namespace fs = std::filesystem;

// The folder a path's file lives in ("." for a bare name).
static fs::path folder_of(const std::string& path) {
    const fs::path folder = fs::path(path).parent_path();
    return folder.empty() ? fs::path(".") : folder;
}

std::optional<std::string> output_path_problem(const std::string& path) {
    struct stat info {};
    const fs::path folder = folder_of(path);
    if (::stat(path.c_str(), &info) == 0 && S_ISDIR(info.st_mode)) return "it is a directory";
    if (::stat(folder.c_str(), &info) != 0) return "no such folder '" + folder.string() + "'";
    if (!S_ISDIR(info.st_mode)) return "'" + folder.string() + "' is not a folder";
    if (::access(folder.c_str(), W_OK | X_OK) != 0)
        return "cannot write in '" + folder.string() + "': " + errno_text(errno);
    return std::nullopt;
}

bool same_file(const std::string& a, const std::string& b) {
    struct stat first {
    }, second{};
    if (::stat(a.c_str(), &first) == 0 && ::stat(b.c_str(), &second) == 0)
        return first.st_dev == second.st_dev && first.st_ino == second.st_ino;
    std::error_code error;
    const fs::path resolved_a = fs::weakly_canonical(fs::absolute(a), error);
    const fs::path resolved_b = fs::weakly_canonical(fs::absolute(b), error);
    return resolved_a == resolved_b;
}

std::optional<std::string> write_file_atomically(const std::string& path, std::string_view bytes) {
    // Step 1: a new temporary file beside the target (same file system, so rename is atomic).
    const fs::path target(path);
    std::string temporary = (folder_of(path) / ("." + target.filename().string() + ".XXXXXX")).string();
    const int fd = ::mkstemp(temporary.data());
    if (fd < 0) return errno_text(errno);
    const mode_t mask = ::umask(0);  // mkstemp makes 0600; give the file the usual 0666 & ~umask
    ::umask(mask);
    ::fchmod(fd, 0666 & ~mask);

    // Step 2: every byte written, flushed to the disk, and the file closed without error.
    std::optional<std::string> problem;
    size_t done = 0;
    while (done < bytes.size() && !problem) {
        const ssize_t wrote = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (wrote < 0 && errno == EINTR) continue;
        if (wrote <= 0)
            problem = errno_text(wrote < 0 ? errno : EIO);
        else
            done += size_t(wrote);
    }
    if (!problem && ::fsync(fd) != 0) problem = errno_text(errno);
    if (::close(fd) != 0 && !problem) problem = errno_text(errno);

    // Step 3: in place of the old file, or removed.
    if (!problem && ::rename(temporary.c_str(), path.c_str()) != 0) problem = errno_text(errno);
    if (problem) {
        ::unlink(temporary.c_str());
        return problem;
    }
    const int folder = ::open(folder_of(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (folder >= 0) {  // the rename itself made durable; failing here loses nothing
        ::fsync(folder);
        ::close(folder);
    }
    return std::nullopt;
}

}  // namespace tracer
