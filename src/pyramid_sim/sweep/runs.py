"""A sweep's builds, run by the job runner (worker processes or Ray tasks): each grid point is
one `run_one`, and each finished run goes to one callback in the calling process (which writes
the CSV), so both backends give the same rows. A run that raises, kills its worker, or passes
the timeout becomes a failed row with its reason; the sweep goes on.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable
from contextlib import closing
from dataclasses import dataclass
from typing import Any

from ..jobs.runner import run_jobs
from ..output.result import BuildResult
from .grid import SweepRun
from .store import KEY_COLUMNS, RESULT_FIELDS


@dataclass(frozen=True)
class RunResult:
    """A finished run: its CSV row and, when the build ran to its end, its BuildResult."""

    spec: SweepRun
    row: dict[str, Any]
    build: BuildResult | None = None


OnResult = Callable[[RunResult], None]


def make_row(spec: SweepRun, wall: float, reason: str | None, **results: Any) -> dict[str, Any]:
    row: dict[str, Any] = dict(zip(KEY_COLUMNS, spec.key()))
    row.update({name: None for name in RESULT_FIELDS}, success=False)
    row.update(results)
    row["wall_time_s"] = round(wall, 3)
    row["failure_reason"] = " ".join(reason.split()) if reason else None  # one line in the CSV
    return row


def failed(spec: SweepRun, reason: str, wall: float) -> RunResult:
    return RunResult(spec, make_row(spec, wall, reason))


def run_one(spec: SweepRun) -> RunResult:
    """One full headless build of a grid point (in a worker). Never raises for a run's own
    failure: an exception becomes a failed row naming it."""
    start = time.perf_counter()
    try:
        from ..core.plan import make_plan
        from ..jobs.build import run_build

        config = spec.config()
        result = run_build(make_plan(spec.structure, config, spec.arms), config)
    except Exception as err:  # the sweep goes on; the row says what happened
        return failed(spec, f"crashed: {type(err).__name__}: {err}", time.perf_counter() - start)
    row = make_row(
        spec,
        time.perf_counter() - start,
        result.failure_reason,
        **{name: getattr(result, name) for name in RESULT_FIELDS},
    )
    return RunResult(spec, row, result)


def run_builds(
    specs: Iterable[SweepRun],
    workers: int,
    timeout: float,
    on_result: OnResult,
    backend: str = "process",
    address: str | None = None,
    run: Callable[[SweepRun], RunResult] = run_one,
) -> None:
    """Run every spec on `workers` processes (or Ray tasks, on the cluster at `address`), each
    finished run, or its failed row, handed to `on_result` as it lands."""
    ends = run_jobs(
        run,
        specs,
        workers=workers,
        timeout=timeout,
        backend=backend,
        address=address,
        warm=("pyramid_sim.jobs.build",),  # MuJoCo and mink imported before the clock starts
    )
    with closing(ends):  # a failing callback, or an interrupt, stops every worker at once
        for end in ends:
            on_result(
                end.value if end.failure is None else failed(end.job, end.failure, end.wall_s)
            )
