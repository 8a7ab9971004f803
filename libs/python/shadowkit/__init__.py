"""shadowkit: shadow-map set-ups and their error against ray-traced truth.

setup(...), local_setup(...), Evaluator and evaluate(...) come from the compiled bindings
(shadowkit._native);
shadowkit.sweep runs grids of `shadowkit eval` here or on a Dask cluster.
"""
from ._native import *  # noqa: F401,F403 (setup, local_setup, Evaluator, evaluate, data_directory)
from ._native import __version__  # noqa: F401
