#include "base/diagnostics.h"

#include <algorithm>
#include <climits>
#include <ostream>
#include <sstream>
#include <tuple>

namespace tracer {

Location Diagnostics::locate(const SourceFile& file, Span span) {
    LineCol start = file.locate(span.begin);
    Location location;
    location.path = file.path();
    location.line = start.line;
    location.column = start.column;
    location.line_text = std::string(file.line_text(start.line));
    // Underline the token, but never past the end of its line.
    int available = int(location.line_text.size()) - (start.column - 1);
    location.length = std::clamp(int(span.end) - int(span.begin), 1, std::max(available, 1));
    return location;
}

Location Diagnostics::whole_file(const std::string& path) {
    Location location;
    location.path = path;
    return location;
}

Diagnostic* Diagnostics::report(Severity severity, Location location, std::string message) {
    if (severity == Severity::Error) {
        if (saturated()) return nullptr;
        ++errors_;
    } else if (severity == Severity::Warning) {
        ++warnings_;
    }
    list_.push_back({severity, std::move(location), std::move(message), {}});
    return &list_.back();
}

Diagnostic* Diagnostics::error(const SourceFile& file, Span span, std::string message) {
    return report(Severity::Error, locate(file, span), std::move(message));
}

Diagnostic* Diagnostics::warning(const SourceFile& file, Span span, std::string message) {
    return report(Severity::Warning, locate(file, span), std::move(message));
}

void Diagnostics::note(Diagnostic* parent, const SourceFile& file, Span span, std::string message) {
    if (parent) parent->notes.push_back({Severity::Note, locate(file, span), std::move(message), {}});
}

static const char* severity_name(Severity severity) {
    switch (severity) {
        case Severity::Error: return "error";
        case Severity::Warning: return "warning";
        case Severity::Note: return "note";
    }
    return "error";
}

static void format_one(std::ostream& out, const Diagnostic& d) {
    const Location& at = d.location;
    out << at.path;
    if (at.line > 0) out << ':' << at.line << ':' << at.column;
    out << ": " << severity_name(d.severity) << ": " << d.message << '\n';
    if (at.line == 0) return;
    out << at.line_text << '\n';
    // Keep tabs in the caret line so the caret lines up under tab-indented text.
    std::string pad;
    for (int i = 0; i < at.column - 1 && i < int(at.line_text.size()); ++i)
        pad += at.line_text[i] == '\t' ? '\t' : ' ';
    out << pad << '^' << std::string(std::max(at.length - 1, 0), '~') << '\n';
}

std::string format_diagnostic(const Diagnostic& diagnostic) {
    std::ostringstream out;
    format_one(out, diagnostic);
    for (const Diagnostic& note : diagnostic.notes) format_one(out, note);
    return out.str();
}

void Diagnostics::print(std::ostream& out) const {
    // File by file (in the order they first come up), each in line order whatever stage found
    // them; whole-file messages last within their file.
    std::vector<std::string> files;
    for (const Diagnostic& d : list_)
        if (std::find(files.begin(), files.end(), d.location.path) == files.end()) files.push_back(d.location.path);
    auto key = [&](const Diagnostic* d) {
        const Location& at = d->location;
        const auto file = std::find(files.begin(), files.end(), at.path) - files.begin();
        return std::tuple(file, at.line == 0 ? INT_MAX : at.line, at.column);
    };
    std::vector<const Diagnostic*> ordered;
    for (const Diagnostic& d : list_) ordered.push_back(&d);
    std::stable_sort(ordered.begin(), ordered.end(),
                     [&](const Diagnostic* a, const Diagnostic* b) { return key(a) < key(b); });
    for (const Diagnostic* d : ordered) out << format_diagnostic(*d);
    if (saturated())
        out << "error: stopped after " << kMaxErrors << " errors; fix these and run again to see any others\n";
}

}  // namespace tracer
