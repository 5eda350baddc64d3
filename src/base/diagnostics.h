// Errors, warnings and notes about a scene, printed as
//   file:line:col: error: message
//   <the source line>
//   <a caret under the offending token>
// The collector stops accepting errors after a limit so one mistake cannot flood the terminal.
#pragma once

#include <deque>
#include <iosfwd>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/source.h"

namespace tracer {

enum class Severity { Error, Warning, Note };

// A resolved position: enough to print a message without the source file at hand.
struct Location {
    std::string path;
    int line = 0;  // 0: the message concerns the whole file
    int column = 0;
    int length = 1;         // characters to underline
    std::string line_text;  // the line, or on a very long line a window of it around the column
    int text_column = 1;    // the column at which line_text starts (1 unless windowed)
};

struct Diagnostic {
    Severity severity = Severity::Error;
    Location location;
    std::string message;
    std::vector<Diagnostic> notes;
    // The same diagnostic at the same place in other loop iterations, calls or inclusions,
    // reported once (with the first one's values) and counted here.
    int repeats = 0;
    enum class RepeatedIn : uint8_t { Inclusions, Iterations, Calls };
    RepeatedIn repeated_in = RepeatedIn::Inclusions;
};

class Diagnostics {
public:
    static constexpr int kMaxErrors = 20;        // shown: the first in file order
    static constexpr int kMaxErrorsFound = 200;  // the search stops here: later stages find earlier lines
    // The search stops too after this many errors raised again at a place already reported (in
    // another iteration or call): each costs the run an unwinding, and they only repeat.
    static constexpr int kMostRepeatsCounted = 10000;
    static constexpr int kMaxWarnings = 20;     // more are counted, not kept
    static constexpr size_t kMaxPrints = 1000;  // a scene's print(...) lines kept; more are counted

    // A line a scene printed (`print(...)`): where, and the text.
    struct Printed {
        Location location;
        std::string text;
    };

    // Resolves `span` in `file` into a printable location.
    static Location locate(const SourceFile& file, Span span);
    // A location for a message about a whole file.
    static Location whole_file(const std::string& path);

    // Records a diagnostic; errors and warnings past their limits are counted and dropped.
    // Returns the stored one (or nullptr when dropped) so notes can be attached.
    Diagnostic* report(Severity severity, Location location, std::string message);
    Diagnostic* error(const SourceFile& file, Span span, std::string message);
    Diagnostic* warning(const SourceFile& file, Span span, std::string message);
    // Attaches a note pointing at `span` to `parent` (no-op when parent is null).
    static void note(Diagnostic* parent, const SourceFile& file, Span span, std::string message);
    // The same for spans of a whole scene (its included files, its loops): located in their
    // own file, errors and warnings followed by notes saying where the text came from. One
    // raised again at the same place in another iteration or inclusion only counts as a repeat
    // of the first (returning nullptr): the error limits count distinct places.
    static Location locate(const Sources& sources, Span span);
    Diagnostic* error(const Sources& sources, Span span, std::string message);
    Diagnostic* warning(const Sources& sources, Span span, std::string message);
    static void note(Diagnostic* parent, const Sources& sources, Span span, std::string message);
    static void note(Diagnostic* parent, Location location, std::string message);

    // How many diagnostics are kept so far, and the last error kept after such a count (or
    // nullptr): a later stage attaches its note to the errors an earlier call reported.
    size_t mark() const { return list_.size(); }
    Diagnostic* last_error_since(size_t mark);

    int error_count() const { return errors_; }
    int warning_count() const { return warnings_; }
    bool has_errors() const { return errors_ > 0; }
    // True once kMaxErrorsFound errors are kept, or kMostRepeatsCounted repeats of them counted:
    // callers stop looking for more.
    bool saturated() const { return errors_ >= kMaxErrorsFound || error_repeats_ >= kMostRepeatsCounted; }
    const std::deque<Diagnostic>& all() const { return list_; }

    // Keeps a line a scene printed, in the order printed (past kMaxPrints, only counted).
    void printed(Location location, std::string text);
    // True once kMaxPrints lines are kept: a caller may skip writing the next one out.
    bool prints_full() const { return prints_.size() >= kMaxPrints; }
    const std::vector<Printed>& prints() const { return prints_; }
    size_t prints_not_kept() const { return prints_not_kept_; }

    // The diagnostics kept, file by file (in the order they first come up), each file in line
    // order whatever stage found them; whole-file messages last within their file.
    std::vector<const Diagnostic*> in_print_order() const;
    // Prints the lines the scene printed, in their order, then the diagnostics kept in print
    // order (of the errors, the first kMaxErrors), then notices of any limit hit.
    void print(std::ostream& out) const;

private:
    // The diagnostic first reported at a place of a scene's text, and the origin it came from.
    struct Place {
        const SourceFile* file;
        uint32_t begin, end;
        Severity severity;
        auto operator<=>(const Place&) const = default;
    };
    struct FirstAt {
        Diagnostic* diagnostic;
        uint32_t origin;
    };
    // The first diagnostic at `span`'s place from another origin (now counted a repeat), or null.
    Diagnostic* repeat_of(const Sources& sources, Span span, Severity severity);
    void remember(const Sources& sources, Span span, Severity severity, Diagnostic* diagnostic);

    std::deque<Diagnostic> list_;  // a deque: returned pointers stay valid
    std::map<Place, FirstAt> first_at_;
    int errors_ = 0;
    int error_repeats_ = 0;
    int warnings_ = 0;
    std::vector<Printed> prints_;
    size_t prints_not_kept_ = 0;
};

// `text` in single quotes for a message: at most 40 characters (then "..."), control bytes
// shown as \xNN, so neither a megabyte token nor binary data reaches the terminal whole.
std::string in_quotes(std::string_view text);

// "error", "warning" or "note".
const char* severity_name(Severity severity);

// Formats one diagnostic (and its notes) exactly as `print` does.
std::string format_diagnostic(const Diagnostic& diagnostic);

}  // namespace tracer
