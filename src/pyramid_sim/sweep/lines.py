"""The plot of a sweep over one parameter (or none): success rate, worst placement error and
max slip against the parameter's value, every run a point, the mean a line and the spread
between the runs of a point a band. A heatmap of one row would leave an axis empty.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

from ..config import SimConfig
from ..output.result import Tolerances
from .grid import SweepConfig
from .report import axis_values, number, plot_title, save_plot
from .store import SweepRow

if TYPE_CHECKING:
    from matplotlib.axes import Axes

UNPLACED_COLOUR = "#d7301f"


def _by_value(rows: list[SweepRow], name: str) -> dict[float, list[SweepRow]]:
    groups: dict[float, list[SweepRow]] = {}
    for r in rows:
        groups.setdefault(float(r[name]), []).append(r)
    return groups


def _statistics(
    groups: dict[float, list[SweepRow]], column: str, unplaced: bool
) -> tuple[
    list[float], list[float], list[float], list[float], list[tuple[float, float]], list[float]
]:
    """Per value of the swept parameter: the mean, lowest and highest of the runs' values (where
    any was measured), each run's point, and a cross for each run with no value if `unplaced`."""
    xs: list[float] = []
    means: list[float] = []
    lows: list[float] = []
    highs: list[float] = []
    points: list[tuple[float, float]] = []
    crosses: list[float] = []
    for value in sorted(groups):
        found = [number(r[column]) for r in groups[value]]
        finite = [v for v in found if not math.isnan(v)]
        points += [(value, v) for v in finite]
        crosses += [value] * (len(found) - len(finite) if unplaced else 0)
        if finite:
            xs.append(value)
            means.append(sum(finite) / len(finite))
            lows.append(min(finite))
            highs.append(max(finite))
    return xs, means, lows, highs, points, crosses


def _spread(
    ax: Axes,
    groups: dict[float, list[SweepRow]],
    column: str,
    limit: float,
    limit_text: str,
    unplaced: bool,
) -> None:
    """Each run's value as a point, the mean over the runs of a value as a line, their range as
    a band; with `unplaced`, a run with no value (a brick never placed) is a red cross along
    the top. A run with no value otherwise measured nothing and is left out."""
    xs, means, lows, highs, points, crosses = _statistics(groups, column, unplaced)
    top = max([limit, *highs]) * 1.15
    if len(xs) == 1:  # one value: a bar from the lowest run to the highest, the mean a tick
        ax.errorbar(
            xs,
            means,
            yerr=[[means[0] - lows[0]], [highs[0] - means[0]]],
            fmt="_",
            color="#3182bd",
            markersize=24,
            capsize=6,
            label="mean and range",
        )
    elif xs:
        if any(h > lo for h, lo in zip(highs, lows)):  # repeats that differ
            ax.fill_between(
                xs,
                lows,
                highs,
                color="#3182bd",
                alpha=0.18,
                linewidth=0,
                label="range over the runs",
            )
        ax.plot(xs, means, "-", color="#3182bd", linewidth=1.5, label="mean")
    _runs(ax, points, crosses, top)
    ax.axhline(limit, color="#636363", linestyle="--", linewidth=1, label=limit_text)
    ax.set_ylim(0, top * 1.1)
    ax.legend(
        loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=3, fontsize=7, frameon=False
    )  # below the axes: never over a point


def _runs(ax: Axes, points: list[tuple[float, float]], crosses: list[float], top: float) -> None:
    """Each run's value a point; a run with no brick placed a red cross along the top."""
    if points:
        ax.plot(
            [p[0] for p in points],
            [p[1] for p in points],
            "o",
            color="#08519c",
            markersize=4,
            label="a run",
        )
    if crosses:
        ax.plot(
            crosses,
            [top * 1.04] * len(crosses),
            "x",
            color=UNPLACED_COLOUR,
            markersize=8,
            markeredgewidth=2,
            linestyle="none",
            label="a brick not placed",
        )


def _success(ax: Axes, groups: dict[float, list[SweepRow]]) -> None:
    xs = sorted(groups)
    ok = [sum(r.success for r in groups[x]) for x in xs]
    rates = [k / len(groups[x]) for k, x in zip(ok, xs)]
    ax.plot(xs, rates, "o-", color="#1a9850", linewidth=1.5, markersize=6)
    for x, rate, k in zip(xs, rates, ok):
        ax.annotate(
            f"{k}/{len(groups[x])}",
            (x, rate),
            textcoords="offset points",
            xytext=(0, 7),
            ha="center",
            fontsize=8,
        )
    ax.set_ylim(-0.05, 1.15)


def write_lines(rows: list[SweepRow], config: SweepConfig, path: Path) -> None:
    """Success rate, worst placement error and max slip against the swept parameter, as a PNG
    written atomically (save_plot names its group inside it)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    x, _ = config.plot_axes()
    groups = _by_value(rows, x.name)
    values = axis_values(rows, x)
    fig, axes = plt.subplots(1, 3, figsize=(13.5, 4.8), constrained_layout=True)
    _success(axes[0], groups)
    axes[0].set_title("success rate (builds ok / runs)")
    _spread(
        axes[1],
        groups,
        "worst_error_xy_mm",
        Tolerances().xy_mm,
        f"placing tolerance {Tolerances().xy_mm:g} mm",
        unplaced=True,
    )
    axes[1].set_title("worst placement error (mm)")
    _spread(
        axes[2],
        groups,
        "max_slip_mm",
        SimConfig().slip_limit_mm,
        f"slip limit {SimConfig().slip_limit_mm:g} mm",
        unplaced=False,
    )
    axes[2].set_title("max slip in the hand (mm)")
    span = (values[-1] - values[0]) or max(abs(values[0]) * 0.2, 0.5)
    for ax in axes:
        ax.set_xlim(values[0] - 0.08 * span, values[-1] + 0.08 * span)
        if len(values) <= 12:
            ax.set_xticks(values, [f"{v:g}" for v in values])
        ax.set_xlabel(x.label)
        ax.grid(alpha=0.3)
    fig.suptitle(plot_title(config, x, None, rows), fontsize=10)
    save_plot(fig, path, config, f"lines against {x.label}")
