"""An evaluation at a glance, drawn from its evaluation.json alone (matplotlib, MuJoCo-free):
the bricks each episode placed, and where the failures happened: their kind against the
bricks placed before it (the brick it failed on is the next). In the look of a sweep's
heat maps (sweep/heatmaps.py): the same colour maps, cell labels and grey for nothing.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ...output.files import write_atomic
from .scores import failure_kind

if TYPE_CHECKING:
    from matplotlib.axes import Axes

PLOT_FILE = "evaluation.png"  # beside evaluation.json


def plot_evaluation_file(evaluation: Path, png: Path | None = None) -> Path:
    """The plot of the evaluation.json at `evaluation`, written beside it (or to `png`)."""
    scores = json.loads(evaluation.read_text())
    path = png if png is not None else evaluation.with_name(PLOT_FILE)
    write_evaluation_plot(scores, path)
    return path


def write_evaluation_plot(scores: dict[str, Any], path: Path) -> None:
    """Bricks placed per episode and the failures' kinds by brick, as a PNG written whole."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows, bricks = scores["rows"], int(scores["bricks"])
    fig, (left, right) = plt.subplots(
        1, 2, figsize=(13, 4.2), constrained_layout=True, width_ratios=(3, 2)
    )
    _bricks_per_episode(left, rows, bricks)
    _failures(fig, right, rows, bricks)
    fig.suptitle(title(scores))
    meta = {"Description": f"pyramid-sim evaluation: {title(scores)}"}
    try:
        write_atomic(path, lambda tmp: fig.savefig(tmp, format="png", dpi=110, metadata=meta))
    finally:
        plt.close(fig)


def title(scores: dict[str, Any]) -> str:
    """Whose evaluation on what, and its success rate with its interval."""
    task = scores.get("task", {})
    size = ", ".join(f"{k} {v}" for k, v in task.get("size", {}).items())
    low, high = (100 * v for v in scores["success_rate_95"])
    return (
        f"{scores['policy']} on {task.get('structure', '?')} ({size}), {task.get('robot', '?')}"
        f": {scores['successes']}/{scores['episodes']} successes "
        f"({100 * scores['success_rate']:.0f} %, 95 % interval {low:.0f}-{high:.0f} %)"
    )


def _bricks_per_episode(ax: Axes, rows: list[dict[str, Any]], bricks: int) -> None:
    """A bar an episode, as high as the bricks it placed, coloured from red (none) to green
    (all); a success drawn edged in black."""
    import matplotlib

    cmap = matplotlib.colormaps["RdYlGn"]
    placed = [int(r["bricks_placed"]) for r in rows]
    colours = [cmap(p / bricks if bricks else 0.0) for p in placed]
    edges = ["black" if r["success"] else "none" for r in rows]
    ax.bar(range(len(rows)), placed, color=colours, edgecolor=edges, linewidth=0.6, width=0.85)
    ax.axhline(bricks, color="#444444", linewidth=0.8, linestyle="--")
    ax.set_ylim(0, bricks * 1.08 + 0.1)
    ax.set_xlim(-0.6, len(rows) - 0.4)
    ax.set_xlabel(f"episode (seed {rows[0]['seed']} + index)" if rows else "episode")
    ax.set_ylabel(f"bricks placed (of {bricks})")
    ax.set_title("bricks placed per episode (edged: success)")


def _failures(fig: Any, ax: Axes, rows: list[dict[str, Any]], bricks: int) -> None:
    """A cell a failure kind and bricks placed before it, labelled with its episodes."""
    import matplotlib
    import numpy as np
    from matplotlib import patheffects

    failed = [(failure_kind(r["failure"]) or "other", int(r["bricks_placed"])) for r in rows]
    failed = [f for f, r in zip(failed, rows) if not r["success"]]
    ax.set_title("where the failures happened (episodes)")
    if not failed:
        ax.text(0.5, 0.5, f"no failure in {len(rows)} episodes", ha="center", va="center")
        ax.set_axis_off()
        return
    kinds = sorted({k for k, _ in failed})
    grid = np.zeros((len(kinds), bricks + 1))
    for kind, at in failed:
        grid[kinds.index(kind), min(at, bricks)] += 1
    cmap = matplotlib.colormaps["YlOrRd"].with_extremes(bad="#bdbdbd")
    image = ax.imshow(np.ma.masked_equal(grid, 0), cmap=cmap, vmin=0, aspect="auto")
    for (i, j), n in np.ndenumerate(grid):
        if n:
            stroke = [patheffects.withStroke(linewidth=2, foreground="black")]
            ax.text(j, i, f"{n:.0f}", ha="center", va="center", color="white", path_effects=stroke)
    ax.set_xticks(range(bricks + 1))
    ax.set_xlabel("bricks placed before the failure (it failed on the next)")
    ax.set_yticks(range(len(kinds)), kinds)
    from matplotlib.ticker import MaxNLocator

    fig.colorbar(image, ax=ax, ticks=MaxNLocator(integer=True))
