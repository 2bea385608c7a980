"""What a sweep found: per-point statistics, the summary table, which plot a sweep draws and
under which name, and the heatmaps of a two-parameter sweep (matplotlib; lines.py draws a
one-parameter sweep).

Reads only CSV rows (text), so a report can be redrawn from `sweep.csv` alone.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from ..output.files import write_atomic
from ..params import param
from .grid import Axis, SweepConfig, value_text
from .store import SweepRow, row_key

if TYPE_CHECKING:
    from matplotlib.figure import Figure

SLIP_SCALE_MM = 5.0
MAIN_PLOT = "sweep.png"
PNG_KEY = "pyramid_sim sweep"  # the PNG text chunk naming the group a plot draws
MISSING = "n/a"  # a value no run measured (no brick carried to its release, say)


@dataclass(frozen=True)
class CellStats:
    runs: int
    succeeded: int
    worst_error_mm: float  # over the runs; inf when some brick never reached the structure
    max_slip_mm: float  # nan when no brick was carried to its release

    @property
    def rate(self) -> float:
        return self.succeeded / self.runs if self.runs else math.nan


def number(text: str | None) -> float:
    """A CSV cell as a number; NaN for an empty one (a value the run did not measure)."""
    return float(text) if text not in ("", None) else math.nan


def _stats(rows: list[SweepRow]) -> CellStats:
    errors = [number(r["worst_error_xy_mm"]) for r in rows]
    slips = [s for s in (number(r["max_slip_mm"]) for r in rows) if not math.isnan(s)]
    return CellStats(
        runs=len(rows),
        succeeded=sum(r.success for r in rows),
        worst_error_mm=max((math.inf if math.isnan(e) else e) for e in errors)
        if errors
        else math.nan,
        max_slip_mm=max(slips) if slips else math.nan,
    )


def grid_rows(rows: list[SweepRow], config: SweepConfig) -> list[SweepRow]:
    """The rows of this sweep's grid (a folder may hold rows of other grids too)."""
    keys = {spec.key() for spec in config.runs()}
    return [r for r in rows if row_key(r) in keys]


def group_rows(rows: list[SweepRow], config: SweepConfig) -> list[SweepRow]:
    """The rows of the folder in this sweep's group, which its plot draws: the same robot,
    schedule, structure, size, arms, spawn jitter and held parameters, any value of the swept
    ones and any seed (so two grids of one group share a plot, each point once)."""
    full = config.full_axes()
    fixed = {
        "robot": config.robot,
        "schedule": config.schedule,
        "structure": config.structure.name,
        "size": config.structure.size_text(),
        "arms": config.arms,
        "spawn_jitter_mm": value_text(config.spawn_jitter_mm),
        **{a.name: value_text(a.values[0]) for a in full if len(a.values) == 1},
    }
    return [r for r in rows if all(r[k] == v for k, v in fixed.items())]


def plot_label(config: SweepConfig) -> str:
    """The group a sweep belongs to, as a file name: robot, schedule, structure, size, arms,
    the swept parameters (or `point`), the held ones not at their defaults, spawn jitter."""
    full = config.full_axes()
    swept = "+".join(a.name for a in full if len(a.values) > 1) or "point"
    held = [
        f"{a.name}={value_text(a.values[0])}"
        for a in full
        if len(a.values) == 1 and a.values[0] != param(a.name).default
    ]
    parts = [
        config.robot,
        config.schedule,
        config.structure.name,
        config.structure.size_text(),
        config.arms,
        swept,
        *held,
        f"jitter={config.spawn_jitter_mm:g}",
    ]
    return "_".join(re.sub(r"[^A-Za-z0-9.=+-]+", "-", p) for p in parts)


def png_group(path: Path) -> str | None:
    """The group a plot of ours was drawn for (its PNG text), None for any other file."""
    try:
        from PIL import Image

        with Image.open(path) as image:
            return image.text.get(PNG_KEY)
    except (OSError, ValueError, AttributeError):
        return None


def plot_path(out: Path, config: SweepConfig) -> Path:
    """Where this sweep's plot goes: `sweep.png` when the folder has none yet or that one is
    this group's; else `sweep_<group>.png`, so another group's plot is never drawn over."""
    main = out / MAIN_PLOT
    label = plot_label(config)
    if not main.exists() or png_group(main) == label:
        return main
    return out / f"sweep_{label}.png"


def axis_values(rows: list[SweepRow], axis: Axis) -> tuple[float, ...]:
    """The axis's values in the grid and in the rows drawn, in order."""
    return tuple(sorted({*axis.values, *(float(r[axis.name]) for r in rows)}))


def cells(rows: list[SweepRow], x: Axis, y: Axis | None) -> dict[tuple[str, str | None], CellStats]:
    """Statistics per (x, y) cell, folding repeats and any other varying parameter."""
    groups: dict[tuple[str, str | None], list[SweepRow]] = {}
    for r in rows:
        groups.setdefault((r[x.name], r[y.name] if y else None), []).append(r)
    return {k: _stats(v) for k, v in groups.items()}


def summary_table(rows: list[SweepRow], config: SweepConfig) -> str:
    """One line per grid point: its parameters, successes over runs, worst error, max slip."""
    varying = [a for a in config.full_axes() if len(a.values) > 1] or [config.full_axes()[0]]
    groups: dict[tuple[str, ...], list[SweepRow]] = {}
    for r in rows:
        groups.setdefault(tuple(r[a.name] for a in varying), []).append(r)
    header = [a.label for a in varying] + ["ok/runs", "worst xy mm", "max slip mm"]
    lines = [header]
    for spec_values in sorted(groups, key=lambda k: tuple(float(v) for v in k)):
        s = _stats(groups[spec_values])
        lines.append(
            [
                *spec_values,
                f"{s.succeeded}/{s.runs}",
                cell_text(s.worst_error_mm),
                cell_text(s.max_slip_mm),
            ]
        )
    widths = [max(len(line[i]) for line in lines) for i in range(len(header))]
    return "\n".join("  ".join(c.rjust(w) for c, w in zip(line, widths)) for line in lines)


def cell_text(v: float) -> str:
    if math.isnan(v):
        return MISSING
    return "not placed" if math.isinf(v) else f"{v:.2f}"


def save_plot(fig: Figure, path: Path, config: SweepConfig, what: str) -> None:
    """Write the figure as a PNG, atomically, naming its group and what it shows in its text
    chunks (the group is how a later sweep tells its own plot from another's); closes it."""
    import matplotlib.pyplot as plt

    metadata = {PNG_KEY: plot_label(config), "Description": f"pyramid-sim sweep: {what}"}
    try:
        write_atomic(path, lambda tmp: fig.savefig(tmp, format="png", dpi=110, metadata=metadata))
    finally:
        plt.close(fig)


def plot_title(config: SweepConfig, x: Axis, y: Axis | None, rows: list[SweepRow]) -> str:
    """What the plot shows: the group (robot, schedule, structure), the runs a point, and the
    parameters held or folded."""
    fixed = ", ".join(
        f"{a.label} {value_text(a.values[0])}"
        for a in config.full_axes()
        if len(a.values) == 1 and a.name not in (x.name, y.name if y else None)
    )
    folded = [a.label for a in config.full_axes() if len(a.values) > 1 and a not in (x, y)]
    per_point: dict[tuple[str, ...], int] = {}
    for r in rows:
        point = tuple(r[a.name] for a in config.full_axes())
        per_point[point] = per_point.get(point, 0) + 1
    low, high = min(per_point.values(), default=0), max(per_point.values(), default=0)
    runs = f"{low}" if low == high else f"{low} to {high}"
    return (
        f"{config.robot}, {config.schedule}: {config.structure.name} "
        f"({config.structure.size_text()}, arms {config.arms}), {runs} run(s) a point, "
        f"spawn jitter {config.spawn_jitter_mm:g} mm"
        + (f"; {fixed}" if fixed else "")
        + (f"; cells fold {', '.join(folded)}" if folded else "")
    )
