// A scene file's text and the positions inside it.
// Tokens carry byte offsets only; line and column are computed when a message needs them.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace tracer {

// A half-open byte range [begin, end) in one source file.
struct Span {
    uint32_t begin = 0;
    uint32_t end = 0;
};

// A 1-based line and column (columns count bytes).
struct LineCol {
    int line = 1;
    int column = 1;
};

class SourceFile {
public:
    // Wraps text read from `path` (the path is only used in messages), with lone carriage
    // returns made line feeds and a UTF-8 byte-order mark made spaces (offsets unchanged).
    SourceFile(std::string path, std::string text);

    const std::string& path() const { return path_; }
    std::string_view text() const { return text_; }
    std::string_view slice(Span span) const;

    // Line and column of a byte offset.
    LineCol locate(uint32_t offset) const;
    // The text of a 1-based line, without its line break.
    std::string_view line_text(int line) const;

private:
    std::string path_;
    std::string text_;
    std::vector<uint32_t> line_starts_;
};

}  // namespace tracer
