// A scene file's text and the positions inside it.
// Tokens carry byte offsets only; line and column are computed when a message needs them.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace tracer {

// A half-open byte range [begin, end) in one source file; `origin` says which file and in what
// context the text was evaluated (an index into Sources; 0: the scene file itself).
struct Span {
    uint32_t begin = 0;
    uint32_t end = 0;
    uint32_t origin = 0;
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

// Every source text of one scene (the scene file and the files it includes) and the contexts
// its values were made in (an include, a loop iteration): what a Span's `origin` indexes.
class Sources {
public:
    // The scene file; its spans have origin 0.
    explicit Sources(std::unique_ptr<SourceFile> scene);

    // A file included by the statement at `included_at`; returns the origin of its spans.
    uint32_t add_include(std::unique_ptr<SourceFile> file, Span included_at);
    // The file of `origin` included once more, by the statement at `included_at` (its text is
    // held once however often it is included).
    uint32_t add_include_again(uint32_t origin, Span included_at);
    // An iteration of the loop at `loop` with `name` = `value`: spans of text evaluated in it
    // get the returned origin (they lie in the loop's file). `name` must outlive this object
    // (a view of a source text held here).
    uint32_t add_iteration(Span loop, std::string_view name, double value);
    // A call of the function `name` (whose body lies in the file of `body_origin`) made at
    // `called_at`: spans of its body evaluated in that call get the returned origin. `name` must
    // outlive this object, as for add_iteration.
    uint32_t add_call(uint32_t body_origin, Span called_at, std::string_view name);
    // A value used at `used_at` that the command line set (`text`: "-D NAME=VALUE"): messages
    // about a span with the returned origin say so in a note.
    uint32_t add_command_line(Span used_at, std::string text);

    const SourceFile& scene() const { return *files_.front(); }
    // Every file read: the scene, then each included file once, in the order first included.
    size_t files() const { return files_.size(); }
    const SourceFile& file_at(size_t index) const { return *files_[index]; }
    // The file a span lies in.
    const SourceFile& file(Span span) const { return *files_[origins_[span.origin].file]; }
    // One level of where a span's text came from: the explaining span, its text ("in iteration
    // i = 5 of this loop", "included from here") and, for a call, the function's name.
    struct Level {
        Span at;
        std::string text;
        std::string_view called;  // empty unless a call
    };
    // Where a span's text came from, innermost first.
    std::vector<Level> context(Span span) const;
    // The spans of the include statements above `origin`'s file, innermost first.
    std::vector<Span> include_chain(uint32_t origin) const;
    size_t origins() const { return origins_.size(); }
    // Forgets the origins made since there were `count`: nothing may refer to them any more.
    void forget_origins_from(size_t count) {
        if (count < origins_.size()) origins_.resize(count);
    }
    // True if `origin` is a loop iteration (else a call, a file, the scene or an include).
    bool is_iteration(uint32_t origin) const { return kind_around(origin) == Kind::Iteration; }
    // True if `origin` is a call of a function.
    bool is_call(uint32_t origin) const { return kind_around(origin) == Kind::Call; }

private:
    enum class Kind : uint8_t { File, Iteration, Call, CommandLine };
    struct Origin {
        uint32_t file = 0;
        Kind kind = Kind::File;  // File: the file itself, included at `at` (unless it is the scene)
        Span at;                 // the loop, the call or the include statement
        std::string_view name;   // the loop's variable, or the function called
        double value = 0;
    };
    // The kind of `origin`, seen through a command-line note to the context it was used in.
    Kind kind_around(uint32_t origin) const {
        const Origin& o = origins_[origin];
        return o.kind == Kind::CommandLine ? origins_[o.at.origin].kind : o.kind;
    }
    std::vector<std::unique_ptr<SourceFile>> files_;
    std::vector<Origin> origins_;
    std::deque<std::string> texts_;  // the command-line texts origins name (a deque: they stay put)
};

}  // namespace tracer
