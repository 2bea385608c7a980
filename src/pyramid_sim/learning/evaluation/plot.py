"""An evaluation at a glance, drawn from its evaluation.json alone (matplotlib, MuJoCo-free):
the bricks each episode placed, and where the failures happened: on which brick, of which kind,
and in which primitive (each row's `failed_at`, failure_site.py). In the look of a sweep's
heat maps (sweep/heatmaps.py): the same colour maps, cell labels and grey for nothing.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ...output.files import write_atomic
from .failure_site import SCENE_PHASES
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
    fig, (left, *right) = plt.subplots(
        1, 3, figsize=(17, 4.4), constrained_layout=True, width_ratios=(3, 2, 2)
    )
    _bricks_per_episode(left, rows, bricks)
    _failures(fig, (right[0], right[1]), rows, bricks)
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
    (all); a success drawn edged in black, an episode that placed none a red cross."""
    import matplotlib
    from matplotlib.ticker import MaxNLocator

    cmap = matplotlib.colormaps["RdYlGn"]
    placed = [int(r["bricks_placed"]) for r in rows]
    colours = [cmap(p / bricks if bricks else 0.0) for p in placed]
    edges = ["black" if r["success"] else "none" for r in rows]
    ax.bar(range(len(rows)), placed, color=colours, edgecolor=edges, linewidth=0.6, width=0.85)
    none = [i for i, p in enumerate(placed) if p == 0]  # a bar of height 0 draws nothing
    ax.plot(none, [0] * len(none), "x", color=cmap(0.0), markersize=9, mew=2, clip_on=False)
    ax.axhline(bricks, color="#444444", linewidth=0.8, linestyle="--")
    ax.set_ylim(0, bricks * 1.08 + 0.1)
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))  # episodes and bricks are whole
    ax.yaxis.set_major_locator(MaxNLocator(integer=True))
    ax.set_xlim(-0.6, len(rows) - 0.4)
    ax.set_xlabel(f"episode (seed {rows[0]['seed']} + index)" if rows else "episode")
    ax.set_ylabel(f"bricks placed (of {bricks})")
    ax.set_title("bricks placed per episode (edged: success; x: none)")


# the primitives in the order a brick passes them (the script's, then the scene's readings)
STEPS = ("hover", "approach", "servo", "grip", "release", "retract")
ORDER = (
    *(f"pick {s}" for s in STEPS if s != "release"),
    *(f"place {s}" for s in STEPS if s not in ("approach", "grip")),
    *(f"build {s}" for s in STEPS),
    *SCENE_PHASES,
)


def failure_sites(rows: list[dict[str, Any]]) -> list[tuple[str, str, int | None]]:
    """Each failed episode's kind, primitive and brick (build order; None: after the last).
    A file from before `failed_at` was recorded: the brick after those placed, the primitive
    `not recorded`."""
    sites: list[tuple[str, str, int | None]] = []
    for r in rows:
        if r["success"]:
            continue
        kind = failure_kind(r["failure"]) or "other"
        at = r.get("failed_at")
        if at is None:
            sites.append((kind, "not recorded", int(r["bricks_placed"])))
        else:
            sites.append((kind, str(at["primitive"]), at["brick"]))
    return sites


Grid = tuple[list[str], list[str], list[list[int]]]  # row names, column names, counts


def failure_grids(rows: list[dict[str, Any]], bricks: int) -> dict[str, Grid]:
    """The failed episodes counted by `kind` and by `primitive` (the grids' rows, in the order
    a brick passes the primitives) against the brick each failed on (the columns: build order,
    and `after` for a failure once every target held a brick); empty with no failure."""
    sites = failure_sites(rows)
    if not sites:
        return {}
    columns: list[int | None] = list(range(bricks))
    if any(b is None or b >= bricks for _, _, b in sites):
        columns.append(None)
    labels = [str(b) if b is not None else "after" for b in columns]
    kinds = sorted({k for k, _, _ in sites})
    prims = sorted({p for _, p, _ in sites}, key=lambda p: (_rank(p), p))
    grids = {}
    for what, names, pick in (("kind", kinds, 0), ("primitive", prims, 1)):
        counts = [[0] * len(columns) for _ in names]
        for site in sites:
            column = columns.index(site[2]) if site[2] in columns else len(columns) - 1
            counts[names.index(str(site[pick]))][column] += 1
        grids[what] = (names, labels, counts)
    return grids


def _rank(primitive: str) -> float:
    """Where a primitive comes in a brick's passage: waiting to enter before the action's
    first move, done and waiting after its last; one not in `ORDER` after them all."""
    action, bump = primitive.split(" ")[0], 0.0
    if primitive.endswith(" waiting to enter"):
        primitive, bump = f"{action} hover", -0.5
    elif primitive.endswith(" done, waiting"):
        primitive, bump = f"{action} retract", 0.5
    return ORDER.index(primitive) + bump if primitive in ORDER else len(ORDER)


def _failures(fig: Any, axes: tuple[Axes, Axes], rows: list[dict[str, Any]], bricks: int) -> None:
    """Two grids of failed episodes against the brick each failed on: by kind, and by the
    primitive its arm was in (the script's or the scene's reading, as the title says)."""
    grids = failure_grids(rows, bricks)
    reads = sorted({r["failed_at"]["read"] for r in rows if r.get("failed_at")})
    read = f" (read from the {' and the '.join(reads)})" if reads else ""
    for ax, what in zip(axes, ("kind", "primitive")):
        ax.set_title(f"failures by {what}{read if what == 'primitive' else ''} and brick")
        if not grids:
            ax.text(0.5, 0.5, f"no failure in {len(rows)} episodes", ha="center", va="center")
            ax.set_axis_off()
            continue
        _grid(fig, ax, *grids[what])
        ax.set_xlabel("brick it failed on (build order)")


def _grid(fig: Any, ax: Axes, rows: list[str], cols: list[str], counts: list[list[int]]) -> None:
    """A heat map of counts, each cell labelled, grey where nothing failed (a sweep's look)."""
    import matplotlib
    import numpy as np
    from matplotlib import patheffects
    from matplotlib.ticker import MaxNLocator

    grid = np.array(counts, dtype=float)
    cmap = matplotlib.colormaps["YlOrRd"].with_extremes(bad="#bdbdbd")
    image = ax.imshow(np.ma.masked_equal(grid, 0), cmap=cmap, vmin=0, aspect="auto")
    stroke = [patheffects.withStroke(linewidth=2, foreground="black")]
    for (i, j), n in np.ndenumerate(grid):
        if n:
            ax.text(j, i, f"{n:.0f}", ha="center", va="center", color="white", path_effects=stroke)
    every = 1 if len(cols) <= 12 else 2 if len(cols) <= 24 else 5  # labels that do not touch
    shown = [c if k % every == 0 or not c.isdigit() else "" for k, c in enumerate(cols)]
    ax.set_xticks(range(len(cols)), shown)
    ax.set_yticks(range(len(rows)), rows)
    fig.colorbar(image, ax=ax, ticks=MaxNLocator(integer=True), label="episodes")
