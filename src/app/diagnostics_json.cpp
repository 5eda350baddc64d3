#include "app/diagnostics_json.h"

#include <sstream>

namespace tracer {

nlohmann::json diagnostic_json(const Diagnostic& diagnostic) {
    const Location& at = diagnostic.location;
    nlohmann::json notes = nlohmann::json::array();
    for (const Diagnostic& note : diagnostic.notes) notes.push_back(diagnostic_json(note));
    return {{"severity", severity_name(diagnostic.severity)},
            {"path", at.path},
            {"line", at.line},
            {"column", at.column},
            {"length", at.length},
            {"message", diagnostic.message},
            {"text", format_diagnostic(diagnostic)},
            {"repeats", diagnostic.repeats},
            {"notes", std::move(notes)}};
}

nlohmann::json load_report_json(const std::string& scene, const LoadReport& report) {
    nlohmann::json diagnostics = nlohmann::json::array();
    for (const Diagnostic* diagnostic : report.diagnostics.in_print_order())
        diagnostics.push_back(diagnostic_json(*diagnostic));
    std::ostringstream text;
    report.diagnostics.print(text);
    nlohmann::json prints = nlohmann::json::array();
    for (const Diagnostics::Printed& line : report.diagnostics.prints())
        prints.push_back({{"path", line.location.path},
                          {"line", line.location.line},
                          {"column", line.location.column},
                          {"length", line.location.length},
                          {"text", line.text}});
    nlohmann::json names = nlohmann::json::array();
    if (report.names)
        for (const DefinedName& defined : *report.names)
            names.push_back({{"name", defined.name},
                             {"kind", defined.kind},
                             {"path", defined.path},
                             {"line", defined.line},
                             {"column", defined.column}});
    return {{"scene", scene},
            {"ok", !report.diagnostics.has_errors()},
            {"errors", report.diagnostics.error_count()},
            {"warnings", report.diagnostics.warning_count()},
            {"diagnostics", std::move(diagnostics)},
            {"prints", std::move(prints)},
            {"prints_not_kept", report.diagnostics.prints_not_kept()},
            {"text", text.str()},
            {"files_read", report.files_read},
            {"unreadable", report.unreadable},
            {"names", std::move(names)}};
}

std::string json_line(const nlohmann::json& value) {
    return value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + '\n';
}

}  // namespace tracer
