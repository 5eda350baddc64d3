"""NFF (Eric Haines' Neutral File Format) import: tools/nff2scn converts an NFF file to tracer's language."""
