// Diagnostics as JSON for other programs (`--diagnostics json`): editors, the preview page.
#pragma once

#include <nlohmann/json.hpp>

#include "app/load_files.h"

namespace tracer {

// One diagnostic: severity, path, line and column (1-based; columns count bytes; line 0: the
// whole file), length (characters underlined), message, the text a terminal shows for it,
// repeats, notes.
nlohmann::json diagnostic_json(const Diagnostic& diagnostic);

// A whole load: {"scene", "ok", "errors", "warnings", "diagnostics": [...] in the terminal's
// order, "text": what the terminal shows, "files_read": [...], "unreadable": whether the scene
// file itself could not be read, "names": the names the scene
// defines, each with its kind, path, line and column}.
nlohmann::json load_report_json(const std::string& scene, const LoadReport& report);

// One line of JSON text (JSON Lines), bytes that are not UTF-8 replaced.
std::string json_line(const nlohmann::json& value);

}  // namespace tracer
