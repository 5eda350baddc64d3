"""tools/farm: one scene split into tiles, or a list of jobs, rendered by tracer on a Dask cluster."""
