"""The SPD suite (Eric Haines' Standard Procedural Databases) through tracer: tools/spd."""
