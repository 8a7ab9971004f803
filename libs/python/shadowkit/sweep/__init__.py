"""shadowkit.sweep: grids of `shadowkit eval` measured against ray-traced truth, resumable, run
here or on a Dask cluster (docs/sweeps.md).

    python3 -m shadowkit.sweep data/sweeps/techniques.json --out out/sweep
    python3 -m shadowkit.sweep SPEC --out DIR --local-workers 2
    python3 -m shadowkit.sweep SPEC --out DIR --scheduler tcp://HOST:8786

spec.py reads and expands a specification, program.py finds the program and its fingerprint,
cells.py measures a cell, store.py keeps the results, runners.py runs the cells (serially or
on Dask), summary.py writes the tables and the plot, cli.py is the command.
"""
from .cells import rows_of, run_cell
from .cli import main
from .spec import Cell, SpecError, expand, load
from .store import Store

__all__ = ["Cell", "SpecError", "Store", "expand", "load", "main", "rows_of", "run_cell"]
