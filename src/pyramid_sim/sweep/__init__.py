"""Parameter sweeps: the grid, its builds (run by jobs/runner.py on worker processes or Ray), the resumable CSV, and
the plots.

Importing the package imports none of its modules (a run needs MuJoCo, the grid does not);
`__all__` names them.
"""

__all__ = [
    "grid",
    "heatmaps",
    "lines",
    "report",
    "run",
    "runs",
    "store",
]
