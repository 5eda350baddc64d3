"""tools/playground: tracer in the browser (issue 59; docs/playground.md)."""
