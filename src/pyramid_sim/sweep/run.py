"""A parameter sweep from grid to plot: skip the runs already in `sweep.csv`, run the rest on
the chosen backend, append each row as it lands, then draw the group's plot (`sweep.png`, or
`sweep_<group>.png` beside another group's) and print the summary."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from .grid import SweepConfig, value_text
from .heatmaps import write_heatmaps
from .report import grid_rows, group_rows, plot_path, summary_table
from .runs import RunResult, run_builds
from .store import SweepRow, SweepStore


def run_file_name(result: RunResult) -> str:
    spec = result.spec
    params = "_".join(f"{n}={value_text(v)}" for n, v in spec.params)
    size = spec.structure.size_text().replace(" ", "_").replace(":", "-")
    return (
        f"{spec.robot}_{spec.schedule}_{spec.structure.name}_{size}_{spec.arms}_{params}"
        f"_jitter={spec.spawn_jitter_mm:g}"
        f"_seed={spec.seed}.json"
    )


def run_sweep(
    config: SweepConfig,
    out: Path,
    on_row: Callable[[RunResult], None] | None = None,
    on_skip: Callable[[int], object] | None = None,
) -> tuple[list[SweepRow], int]:
    """Run what is missing from `out/sweep.csv` (and, with `config.retry_failed`, what crashed
    or timed out there); returns the grid's rows and how many ran now. Each run's full result
    document goes to `out/runs/`; `on_skip` hears how many runs are not run again."""
    store = SweepStore(out / "sweep.csv")
    done = store.done(config.retry_failed)
    todo = [spec for spec in config.runs() if spec.key() not in done]
    if on_skip is not None:
        on_skip(len(config.runs()) - len(todo))

    def record(result: RunResult) -> None:
        if result.build is not None:
            result.build.save(out / "runs" / run_file_name(result))
        store.append(result.row)
        if on_row is not None:
            on_row(result)

    if todo:
        run_builds(todo, config.workers, config.timeout, record, config.backend, config.ray_address)
    return grid_rows(store.rows, config), len(todo)


def report(rows: list[SweepRow], config: SweepConfig, out: Path) -> tuple[str, Path]:
    """Draw the plot of this sweep's group: every run of the group in `out/sweep.csv`, against
    the swept parameter (lines) or over the first two (heatmaps). Returns the summary table of
    `rows` (this grid's) and the plot's path."""
    from .lines import write_lines

    path = plot_path(out, config)
    drawn = group_rows(SweepStore(out / "sweep.csv").rows, config) or rows
    if sum(len(a.values) > 1 for a in config.full_axes()) <= 1:
        write_lines(drawn, config, path)
    else:
        write_heatmaps(drawn, config, path)
    return summary_table(rows, config), path
