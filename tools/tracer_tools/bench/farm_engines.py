"""Ray against Dask distributed for tools/farm, on this machine: the import, the start of a local
cluster of 2 single-core workers, the round trip of a no-op task and of a task that runs a program
(as each tile runs tracer), the shut-down, and the memory of the cluster's processes. Run it with the
Python of an environment that has the engine (the numbers are in docs/farm.md):

    python3 -m venv /tmp/ray && /tmp/ray/bin/pip install ray==2.60.0 psutil
    PYTHONPATH=tools /tmp/ray/bin/python -m tracer_tools.bench.farm_engines ray
    tools/bench farm-engines dask            # worker processes, as a cluster's (in .venv/)
    tools/bench farm-engines dask-threads    # tools/farm's local default
"""

from __future__ import annotations

import argparse
import json
import logging
import statistics
import subprocess
import sys
import time
from collections.abc import Callable

import psutil

from tracer_tools import option_types


def noop(value: int) -> int:
    return value


def run_program(value: int) -> int:
    subprocess.run(["true"], check=True)
    return value


def cluster_memory_mb() -> float:
    """The resident memory of this process and every process under it."""
    me = psutil.Process()
    return sum(p.memory_info().rss for p in [me, *me.children(recursive=True)]) / 2**20


def measure(engine: str, tasks: int, rounds: int) -> dict:
    figures = {"engine": engine}
    start = time.perf_counter()
    if engine == "ray":
        import ray

        figures["import_s"] = time.perf_counter() - start
        start = time.perf_counter()
        ray.init(num_cpus=2, include_dashboard=False, logging_level="ERROR")
        remote_noop, remote_program = ray.remote(noop), ray.remote(run_program)
        ray.get(remote_noop.remote(0))

        def submit(function: Callable[[int], int], count: int) -> None:
            remote = remote_noop if function is noop else remote_program
            ray.get([remote.remote(i) for i in range(count)])

        def shut_down() -> None:
            ray.shutdown()
    else:
        from distributed import Client, LocalCluster

        figures["import_s"] = time.perf_counter() - start
        start = time.perf_counter()
        cluster = LocalCluster(
            n_workers=2,
            threads_per_worker=1,
            processes=engine == "dask",
            dashboard_address=None,
            silence_logs=logging.CRITICAL,
        )
        client = Client(cluster)
        client.submit(noop, 0).result()

        def submit(function: Callable[[int], int], count: int) -> None:
            client.gather(client.map(function, range(count), pure=False))

        def shut_down() -> None:
            client.close()
            cluster.close()

    figures["start_s"] = time.perf_counter() - start
    figures["memory_mb"] = cluster_memory_mb()
    for name, function in (("noop", noop), ("program", run_program)):
        times = []
        for _ in range(rounds):
            start = time.perf_counter()
            submit(function, tasks)
            times.append(time.perf_counter() - start)
        figures[f"{name}_task_ms"] = 1e3 * statistics.median(times) / tasks
    start = time.perf_counter()
    shut_down()
    figures["shutdown_s"] = time.perf_counter() - start
    return {key: round(value, 4) if isinstance(value, float) else value for key, value in figures.items()}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("engine", choices=["ray", "dask", "dask-threads"])
    parser.add_argument("--tasks", type=option_types.whole_number(1, 1_000_000), default=400)
    parser.add_argument("--rounds", type=option_types.whole_number(1, 1_000_000), default=5)
    arguments = parser.parse_args()
    print(json.dumps(measure(arguments.engine, arguments.tasks, arguments.rounds)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
