"""The benchmarks: each module has a main() that `tools/bench NAME` runs (see __main__.BENCHMARKS)
and writes its report under docs/, with the machine noted (common.machine())."""
