"""Parameter sweeps: the grid, the runners (worker processes or Ray), the resumable CSV, and
the plots.

Importing the package imports none of its modules (a run needs MuJoCo, the grid does not);
`__all__` names them.
"""

__all__ = [
    "backends",
    "grid",
    "heatmaps",
    "lines",
    "ray_backend",
    "report",
    "run",
    "store",
]
