#include "base/source.h"

#include <algorithm>
#include <cstdio>

namespace tracer {

SourceFile::SourceFile(std::string path, std::string text) : path_(std::move(path)), text_(std::move(text)) {
    // Every byte keeps its offset: lone carriage returns (classic Mac line ends) become line
    // feeds, a UTF-8 byte-order mark becomes spaces.
    for (size_t i = 0; i < text_.size(); ++i)
        if (text_[i] == '\r' && (i + 1 == text_.size() || text_[i + 1] != '\n')) text_[i] = '\n';
    if (text_.compare(0, 3, "\xEF\xBB\xBF") == 0) text_[0] = text_[1] = text_[2] = ' ';
    line_starts_.push_back(0);
    for (uint32_t i = 0; i < text_.size(); ++i)
        if (text_[i] == '\n') line_starts_.push_back(i + 1);
}

std::string_view SourceFile::slice(Span span) const {
    return std::string_view(text_).substr(span.begin, span.end - span.begin);
}

LineCol SourceFile::locate(uint32_t offset) const {
    auto next = std::upper_bound(line_starts_.begin(), line_starts_.end(), offset);
    int line = int(next - line_starts_.begin());
    return {line, int(offset - line_starts_[line - 1]) + 1};
}

std::string_view SourceFile::line_text(int line) const {
    if (line < 1 || line > int(line_starts_.size())) return {};
    uint32_t begin = line_starts_[line - 1];
    uint32_t end = line < int(line_starts_.size()) ? line_starts_[line] : uint32_t(text_.size());
    std::string_view text = std::string_view(text_).substr(begin, end - begin);
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.remove_suffix(1);
    return text;
}

Sources::Sources(std::unique_ptr<SourceFile> scene) {
    files_.push_back(std::move(scene));
    origins_.push_back({});
}

uint32_t Sources::add_include(std::unique_ptr<SourceFile> file, Span included_at) {
    files_.push_back(std::move(file));
    origins_.push_back({uint32_t(files_.size() - 1), Kind::File, included_at, {}, 0});
    return uint32_t(origins_.size() - 1);
}

uint32_t Sources::add_include_again(uint32_t origin, Span included_at) {
    origins_.push_back({origins_[origin].file, Kind::File, included_at, {}, 0});
    return uint32_t(origins_.size() - 1);
}

uint32_t Sources::add_iteration(Span loop, std::string_view name, double value) {
    origins_.push_back({origins_[loop.origin].file, Kind::Iteration, loop, name, value});
    return uint32_t(origins_.size() - 1);
}

uint32_t Sources::add_command_line(Span used_at, std::string text) {
    texts_.push_back(std::move(text));
    origins_.push_back({origins_[used_at.origin].file, Kind::CommandLine, used_at, texts_.back(), 0});
    return uint32_t(origins_.size() - 1);
}

uint32_t Sources::add_call(uint32_t body_origin, Span called_at, std::string_view name) {
    origins_.push_back({origins_[body_origin].file, Kind::Call, called_at, name, 0});
    return uint32_t(origins_.size() - 1);
}

std::vector<Sources::Level> Sources::context(Span span) const {
    std::vector<Level> out;
    for (uint32_t origin = span.origin; origin != 0;) {
        const Origin& o = origins_[origin];
        char text[128];
        if (o.kind == Kind::Iteration)
            std::snprintf(text, sizeof text, "in iteration %.*s = %.17g of this loop",
                          int(std::min<size_t>(o.name.size(), 40)), o.name.data(), o.value);
        else if (o.kind == Kind::CommandLine)
            std::snprintf(text, sizeof text, "this value came from the command line: %.*s",
                          int(std::min<size_t>(o.name.size(), 60)), o.name.data());
        else if (o.kind == Kind::Call)
            std::snprintf(text, sizeof text, "in this call of '%.*s'", int(std::min<size_t>(o.name.size(), 40)),
                          o.name.data());
        else
            std::snprintf(text, sizeof text, "included from here");
        out.push_back({o.at, std::string(text), o.kind == Kind::Call ? o.name : std::string_view()});
        origin = o.at.origin;
    }
    return out;
}

std::vector<Span> Sources::include_chain(uint32_t origin) const {
    std::vector<Span> out;
    while (origin != 0) {
        const Origin& o = origins_[origin];
        if (o.kind == Kind::File) out.push_back(o.at);
        origin = o.at.origin;
    }
    return out;
}

}  // namespace tracer
