#include "base/diagnostics.h"

#include <algorithm>
#include <climits>
#include <cstdio>
#include <ostream>
#include <set>
#include <sstream>
#include <string_view>
#include <tuple>
#include <vector>

namespace tracer {

// Lines longer than this are shown as a window around the column.
static constexpr int kLongestShownLine = 160;

// True for the bytes that continue a UTF-8 sequence (a window never starts or ends in one).
static bool continues_utf8(char c) {
    return (static_cast<unsigned char>(c) & 0xC0) == 0x80;
}

Location Diagnostics::locate(const SourceFile& file, Span span) {
    LineCol start = file.locate(span.begin);
    Location location;
    location.path = file.path();
    location.line = start.line;
    location.column = start.column;
    std::string_view line = file.line_text(start.line);
    // A window of a very long line (a minified or binary file): 60 bytes before the column,
    // 100 after, cut at character boundaries.
    if (int(line.size()) > kLongestShownLine) {
        size_t from = size_t(std::max(start.column - 1 - 60, 0));
        while (from > 0 && continues_utf8(line[from])) --from;
        size_t to = std::min(line.size(), size_t(start.column - 1) + 100);
        while (to < line.size() && continues_utf8(line[to])) ++to;
        location.text_column = int(from) + 1;
        line = line.substr(from, to - from);
    }
    location.line_text = std::string(line);
    for (char& c : location.line_text)  // binary data is not sent to the terminal
        if ((static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == 0x7F) c = '?';
    // Underline the token in characters (a UTF-8 sequence is one), never past the text shown.
    const size_t token_start = size_t(std::max(start.column - location.text_column, 0));
    const std::string_view token = std::string_view(location.line_text)
                                       .substr(std::min(token_start, location.line_text.size()),
                                               size_t(std::max(int(span.end) - int(span.begin), 0)));
    location.length =
        std::max(int(std::count_if(token.begin(), token.end(), [](char c) { return !continues_utf8(c); })), 1);
    return location;
}

Location Diagnostics::whole_file(const std::string& path) {
    Location location;
    location.path = path;
    return location;
}

// Messages longer than this are cut (they quote their tokens with in_quotes(); this is a backstop).
static constexpr size_t kLongestMessage = 1000;

Diagnostic* Diagnostics::report(Severity severity, Location location, std::string message) {
    if (severity == Severity::Error) {
        if (saturated()) return nullptr;
        ++errors_;
    } else if (severity == Severity::Warning) {
        if (++warnings_ > kMaxWarnings) return nullptr;
    }
    if (message.size() > kLongestMessage) message = message.substr(0, kLongestMessage) + "...";
    list_.push_back({severity, std::move(location), std::move(message), {}});
    return &list_.back();
}

Diagnostic* Diagnostics::error(const SourceFile& file, Span span, std::string message) {
    if (saturated()) return nullptr;  // before locating: that copies the line
    return report(Severity::Error, locate(file, span), std::move(message));
}

Diagnostic* Diagnostics::warning(const SourceFile& file, Span span, std::string message) {
    if (warnings_ >= kMaxWarnings) {
        ++warnings_;
        return nullptr;
    }
    return report(Severity::Warning, locate(file, span), std::move(message));
}

void Diagnostics::note(Diagnostic* parent, const SourceFile& file, Span span, std::string message) {
    note(parent, locate(file, span), std::move(message));
}

Location Diagnostics::locate(const Sources& sources, Span span) {
    return locate(sources.file(span), span);
}

// The notes saying where a span's text came from: each loop iteration and include around it.
// A chain deeper than a screenful shows its innermost and outermost levels; a recursion (a level
// met twice: the same call, or the same iteration, again) only its innermost and outermost
// level, and in one line between them how many levels and which functions it left out.
static void add_context(Diagnostic* diagnostic, const Sources& sources, Span span) {
    if (!diagnostic) return;
    const auto context = sources.context(span);
    bool recursion = false;
    std::set<std::tuple<const SourceFile*, uint32_t, uint32_t, std::string_view>> levels;
    for (const Sources::Level& level : context)
        recursion =
            recursion || !levels.emplace(&sources.file(level.at), level.at.begin, level.at.end, level.text).second;
    const size_t innermost = recursion ? 1 : 5, outermost = recursion ? 1 : 4;
    for (size_t i = 0; i < context.size(); ++i) {
        const auto& [at, text, called] = context[i];
        if (context.size() <= innermost + outermost + 1 || i < innermost || i >= context.size() - outermost) {
            Diagnostics::note(diagnostic, sources, at, text);
        } else if (i == innermost) {
            const size_t left_out = context.size() - innermost - outermost;
            std::string message = "... and " + std::to_string(left_out) + " more levels of calls and loops";
            if (recursion) {
                std::vector<std::string_view> functions;  // the left-out levels' functions, the first 3
                for (size_t k = innermost; k < context.size() - outermost && functions.size() < 3; ++k) {
                    const std::string_view function = context[k].called;
                    if (!function.empty() && std::find(functions.begin(), functions.end(), function) == functions.end())
                        functions.push_back(function);
                }
                for (size_t k = 0; k < functions.size(); ++k)
                    message += (k == 0 ? ": calls of " : ", ") + in_quotes(functions[k]);
            }
            Location whole = Diagnostics::locate(sources, at);
            whole.line = 0;  // one line: no source shown
            Diagnostics::note(diagnostic, whole, message + " ...");
        }
    }
}

Diagnostic* Diagnostics::repeat_of(const Sources& sources, Span span, Severity severity) {
    const auto found = first_at_.find({&sources.file(span), span.begin, span.end, severity});
    if (found == first_at_.end() || found->second.origin == span.origin) return nullptr;
    ++found->second.diagnostic->repeats;
    if (severity == Severity::Error) ++error_repeats_;
    return found->second.diagnostic;
}

void Diagnostics::remember(const Sources& sources, Span span, Severity severity, Diagnostic* diagnostic) {
    if (!diagnostic) return;
    diagnostic->repeated_in = sources.is_iteration(span.origin) ? Diagnostic::RepeatedIn::Iterations
                              : sources.is_call(span.origin)    ? Diagnostic::RepeatedIn::Calls
                                                                : Diagnostic::RepeatedIn::Inclusions;
    first_at_.emplace(Place{&sources.file(span), span.begin, span.end, severity}, FirstAt{diagnostic, span.origin});
}

Diagnostic* Diagnostics::error(const Sources& sources, Span span, std::string message) {
    if (repeat_of(sources, span, Severity::Error)) return nullptr;
    Diagnostic* d = error(sources.file(span), span, std::move(message));
    remember(sources, span, Severity::Error, d);
    add_context(d, sources, span);
    return d;
}

Diagnostic* Diagnostics::warning(const Sources& sources, Span span, std::string message) {
    if (repeat_of(sources, span, Severity::Warning)) return nullptr;
    Diagnostic* d = warning(sources.file(span), span, std::move(message));
    remember(sources, span, Severity::Warning, d);
    add_context(d, sources, span);
    return d;
}

void Diagnostics::note(Diagnostic* parent, const Sources& sources, Span span, std::string message) {
    if (parent) note(parent, locate(sources, span), std::move(message));
}

void Diagnostics::note(Diagnostic* parent, Location location, std::string message) {
    if (parent) parent->notes.push_back({Severity::Note, std::move(location), std::move(message), {}});
}

Diagnostic* Diagnostics::last_error_since(size_t mark) {
    for (size_t i = list_.size(); i > mark; --i)
        if (list_[i - 1].severity == Severity::Error) return &list_[i - 1];
    return nullptr;
}

std::string in_quotes(std::string_view text) {
    constexpr size_t kLongest = 40;  // characters
    std::string out = "'";
    size_t characters = 0;
    for (size_t i = 0; i < text.size(); ++i) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        if (!continues_utf8(char(c)) && ++characters > kLongest) {
            out += "...";
            break;
        }
        if (c < 0x20 || c == 0x7F) {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\x%02X", c);
            out += escaped;
        } else {
            out += char(c);
        }
    }
    return out + "'";
}

const char* severity_name(Severity severity) {
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
    // One space per character before the column (tabs kept), so that the caret lines up under
    // text with tabs or non-ASCII characters.
    std::string pad;
    for (int i = 0; i < at.column - at.text_column && i < int(at.line_text.size()); ++i)
        if (!continues_utf8(at.line_text[i])) pad += at.line_text[i] == '\t' ? '\t' : ' ';
    out << pad << '^' << std::string(std::max(at.length - 1, 0), '~') << '\n';
}

std::string format_diagnostic(const Diagnostic& diagnostic) {
    std::ostringstream out;
    format_one(out, diagnostic);
    for (const Diagnostic& note : diagnostic.notes) format_one(out, note);
    if (diagnostic.repeats > 0) {  // the count, at the first one's place, without its line again
        const Location& at = diagnostic.location;
        const int n = diagnostic.repeats;
        const char* unit = diagnostic.repeated_in == Diagnostic::RepeatedIn::Iterations ? " in %d more iteration"
                           : diagnostic.repeated_in == Diagnostic::RepeatedIn::Calls    ? " in %d more call"
                                                                                        : " %d more time";
        char count[48];
        std::snprintf(count, sizeof count, unit, n);
        out << at.path << ':' << at.line << ':' << at.column << ": note: the same "
            << severity_name(diagnostic.severity) << count << (n == 1 ? "" : "s")
            << (diagnostic.repeated_in == Diagnostic::RepeatedIn::Inclusions ? " (the file is included again)" : "")
            << '\n';
    }
    return out.str();
}

std::vector<const Diagnostic*> Diagnostics::in_print_order() const {
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
    return ordered;
}

void Diagnostics::printed(Location location, std::string text) {
    if (prints_full()) {
        ++prints_not_kept_;
        return;
    }
    if (text.size() > kLongestMessage) text = text.substr(0, kLongestMessage) + "...";
    prints_.push_back({std::move(location), std::move(text)});
}

void Diagnostics::print(std::ostream& out) const {
    for (const Printed& line : prints_)
        out << line.location.path << ':' << line.location.line << ':' << line.location.column
            << ": print: " << line.text << '\n';
    if (prints_not_kept_ > 0) out << "print: " << prints_not_kept_ << " more lines printed, not shown\n";
    int errors_shown = 0;
    for (const Diagnostic* d : in_print_order()) {
        if (d->severity == Severity::Error && ++errors_shown > kMaxErrors) continue;
        out << format_diagnostic(*d);
    }
    if (warnings_ > kMaxWarnings)
        out << "warning: " << warnings_ - kMaxWarnings << " more warning" << (warnings_ - kMaxWarnings == 1 ? "" : "s")
            << " not shown\n";
    if (errors_ > kMaxErrors) {
        const std::string found = saturated() ? "at least " + std::to_string(errors_) : std::to_string(errors_);
        out << "error: showing the first " << kMaxErrors << " of " << found
            << " errors; fix these and run again to see the others\n";
    }
    if (error_repeats_ >= kMostRepeatsCounted)
        out << "error: the search for errors stopped after " << kMostRepeatsCounted
            << " repeats of those shown (the counts of repeats above are of those); fix these and run again\n";
}

}  // namespace tracer
