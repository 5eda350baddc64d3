"""xcheck: cross-checks tracer's images against Mitsuba 3 (see docs/crosscheck.md)."""

# The plugin names the converted XML uses and xcheck.plugins registers.
PHONG_PLUGIN = "tracer_phong"
WHITTED_PLUGIN = "tracer_whitted"


class ToolError(Exception):
    """A problem the command-line tools report in one line and exit with `exit_code`."""

    exit_code = 1


class MitsubaMissing(ToolError):
    """Mitsuba 3 (or Dr.Jit) cannot be imported."""

    exit_code = 4
