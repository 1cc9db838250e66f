"""Three-dimensional point maps (Andoyer-Deprit variables), their analysis and dask sweeps."""
