"""The authoring loop around tracer: the language server (tools/lsp), the preview page
(tools/preview) and the highlighting grammar's generator (tools/make-grammar), each reusing
tracer's own front end through its JSON outputs (--check --diagnostics json, --language-json,
--watch --diagnostics json)."""
