"""The heatmaps of a sweep over two or more parameters: success, worst placement error and
slip a cell, and on a grip-force by brick-mass map the Coulomb limit of the grip at rest."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..output.result import Tolerances
from .grid import Axis, SweepConfig, value_text
from .report import SLIP_SCALE_MM, axis_values, cell_text, cells, plot_title, save_plot
from .store import SweepRow

if TYPE_CHECKING:
    from matplotlib.figure import Figure


def write_heatmaps(rows: list[SweepRow], config: SweepConfig, path: Path) -> None:
    """Success rate, worst placement error and max slip over the two main axes, as a PNG
    written atomically. Errors beyond the placing tolerance, and bricks never placed, show in
    the colour map's 'over' colour so the envelope's edge stands out."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    x, y = config.plot_axes()
    stats = cells(rows, x, y)
    xs = [value_text(v) for v in axis_values(rows, x)]
    ys = [value_text(v) for v in axis_values(rows, y)] if y else [None]
    panels = [
        ("success rate", lambda s: s.rate, "RdYlGn", 0.0, 1.0, lambda s: f"{s.succeeded}/{s.runs}"),
        (
            "worst placement error (mm)",
            lambda s: s.worst_error_mm,
            "viridis",
            0.0,
            Tolerances().xy_mm,
            lambda s: cell_text(s.worst_error_mm),
        ),
        (
            "max slip in the hand (mm)",
            lambda s: s.max_slip_mm,
            "viridis",
            0.0,
            SLIP_SCALE_MM,
            lambda s: cell_text(s.max_slip_mm),
        ),
    ]
    fig, axes = plt.subplots(
        1, 3, figsize=(4.2 * 3 + 1, 1.2 + 0.65 * len(ys) + 1.6), constrained_layout=True
    )
    for ax, panel in zip(axes, panels):
        _draw_panel(fig, ax, panel, stats, xs, ys, config, x, y)
    fig.suptitle(plot_title(config, x, y, rows))
    save_plot(fig, path, config, "heatmaps over " + " and ".join(a.label for a in (x, y) if a))


def _draw_panel(
    fig: Figure,
    ax: Any,
    panel: tuple,
    stats: dict,
    xs: list,
    ys: list,
    config: SweepConfig,
    x: Axis,
    y: Axis | None,
) -> None:
    """One heatmap: a value a cell, coloured, labelled, and the Coulomb line where it applies."""
    import matplotlib
    import numpy as np
    from matplotlib import patheffects

    title, value, cmap_name, vmin, vmax, label = panel
    grid = np.full((len(ys), len(xs)), np.nan)
    for i, yv in enumerate(ys):
        for j, xv in enumerate(xs):
            if (xv, yv) in stats:
                grid[i, j] = value(stats[(xv, yv)])
    cmap = matplotlib.colormaps[cmap_name].with_extremes(over="#d7301f", bad="#bdbdbd")
    shown = np.where(np.isinf(grid), vmax * 10, grid)
    image = ax.imshow(
        np.ma.masked_invalid(shown),
        origin="lower",
        cmap=cmap,
        vmin=vmin,
        vmax=vmax,
        aspect="auto",
    )
    for i, yv in enumerate(ys):
        for j, xv in enumerate(xs):
            text = label(stats[(xv, yv)]) if (xv, yv) in stats else "not run"
            ax.text(
                j,
                i,
                text,
                ha="center",
                va="center",
                fontsize=8 if len(text) < 7 else 6.5,
                color="white",
                path_effects=[patheffects.withStroke(linewidth=2, foreground="black")],
            )
    ax.set_xticks(range(len(xs)), xs)
    ax.set_xlabel(x.label)
    ax.set_yticks(range(len(ys)), ys if y else [""])
    ax.set_ylabel(y.label if y else "")
    ax.set_title(title)
    _draw_coulomb_limit(ax, config, x, y)
    fig.colorbar(image, ax=ax, extend="neither" if title == "success rate" else "max")


GRAVITY = 9.81


def coulomb_mass_limit(grip_force: Any, pad_friction: float) -> Any:
    """The heaviest brick (kg) two pads pressing with `grip_force` each can hold at rest:
    2 mu F / g, Coulomb's law (element-wise for an array of forces)."""
    return 2.0 * pad_friction * grip_force / GRAVITY


def _draw_coulomb_limit(ax, config: SweepConfig, x: Axis, y: Axis | None) -> None:
    """On a grip force x brick mass map (either way round, pad friction held), the line
    where the bricks' weight equals the pads' friction at rest, in the cells' coordinates."""
    import numpy as np

    if y is None or {x.name, y.name} != {"grip_force", "brick_mass"}:
        return
    pad = next(a for a in config.full_axes() if a.name == "pad_friction")
    if len(pad.values) != 1 or any(np.any(np.diff(a.values) <= 0) for a in (x, y)):
        return  # one line only for one pad friction, and on ordered axes
    force_axis, mass_axis = (x, y) if x.name == "grip_force" else (y, x)
    forces = np.linspace(force_axis.values[0], force_axis.values[-1], 100)
    masses = coulomb_mass_limit(forces, pad.values[0])
    fi = np.interp(forces, force_axis.values, range(len(force_axis.values)))
    mi = np.interp(
        masses, mass_axis.values, range(len(mass_axis.values)), left=np.nan, right=np.nan
    )
    xs, ys = (fi, mi) if x is force_axis else (mi, fi)
    ax.plot(
        xs,
        ys,
        color="white",
        linestyle="--",
        linewidth=1.5,
        label=f"Coulomb limit 2 mu F / g (mu {pad.values[0]:g})",
    )
    ax.legend(loc="upper left", fontsize=7, framealpha=0.6)
