"""Run a sweep's builds in parallel: a pool of worker processes, or Ray tasks.

Both backends run the same function, `run_one`, and hand each finished run to one callback in
the calling process (which writes the CSV), so they give the same rows. A run that raises,
kills its worker, or passes the timeout becomes a failed row with its reason; the sweep goes on.
"""

from __future__ import annotations

import multiprocessing as mp
import multiprocessing.connection
import os
import signal
import sys
import time
from collections import deque
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import Any

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


# --- process backend ---------------------------------------------------------------------------


def _die_with_parent() -> None:
    """A worker of a sweep that was killed stops too, instead of finishing its build unseen."""
    if sys.platform.startswith("linux"):
        import ctypes

        try:
            ctypes.CDLL("libc.so.6").prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
        except (OSError, AttributeError):
            pass


# A build is one thread of MuJoCo and small numpy arrays: BLAS pools only spin. Each worker
# gets one BLAS thread, set before it imports numpy (a spawned process inherits the environment).
ONE_BLAS_THREAD = {"OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}


def _worker_loop(conn: mp.connection.Connection, run: Callable[[SweepRun], RunResult]) -> None:
    _die_with_parent()
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent decides when a sweep stops
    from ..jobs import build  # noqa: F401  import MuJoCo and mink once, before any run

    while True:
        try:
            spec = conn.recv()
        except EOFError:
            return
        if spec is None:
            return
        conn.send(run(spec))


class _Worker:
    def __init__(self, ctx: Any, run: Callable[[SweepRun], RunResult]) -> None:
        self.conn, child = ctx.Pipe()
        self.proc = ctx.Process(target=_worker_loop, args=(child, run), daemon=True)
        saved = {k: os.environ.get(k) for k in ONE_BLAS_THREAD}
        os.environ.update(ONE_BLAS_THREAD)
        try:
            self.proc.start()
        finally:  # the parent keeps its own settings
            for key, value in saved.items():
                if value is None:
                    os.environ.pop(key, None)
                else:
                    os.environ[key] = value
        child.close()
        self.spec: SweepRun | None = None
        self.started = 0.0

    def assign(self, spec: SweepRun) -> None:
        self.spec, self.started = spec, time.monotonic()
        self.conn.send(spec)

    def stop(self) -> None:
        if self.proc.is_alive():
            self.proc.kill()
        self.proc.join()
        self.conn.close()


def run_processes(
    specs: Iterable[SweepRun],
    workers: int,
    timeout: float,
    on_result: OnResult,
    run: Callable[[SweepRun], RunResult] = run_one,
) -> None:
    """Run every spec in a pool of `workers` processes (fresh interpreters, one model each at a
    time); a worker that dies or passes `timeout` seconds on a run is replaced."""
    ctx = mp.get_context("spawn")
    pending = deque(specs)
    idle: list[_Worker] = []
    busy: list[_Worker] = []
    try:
        while pending or busy:
            while pending and len(busy) < workers:
                worker = idle.pop() if idle else _Worker(ctx, run)
                worker.assign(pending.popleft())
                busy.append(worker)
            wait = min(w.started + timeout for w in busy) - time.monotonic()
            waitables = [w.conn for w in busy] + [w.proc.sentinel for w in busy]
            mp.connection.wait(waitables, timeout=max(0.0, wait))
            for worker in list(busy):
                spec = worker.spec
                assert spec is not None
                result = _collect(worker, timeout)
                if result is None:
                    continue
                busy.remove(worker)
                if worker.proc.is_alive():
                    idle.append(worker)
                else:  # crashed or timed out: replaced by a fresh process
                    worker.stop()
                on_result(result)
    finally:
        for worker in idle + busy:
            worker.stop()


def _collect(worker: _Worker, timeout: float) -> RunResult | None:
    """The worker's finished run, a failed row if it died or ran out of time, else None."""
    spec = worker.spec
    assert spec is not None
    elapsed = time.monotonic() - worker.started
    if worker.conn.poll():
        try:
            result: RunResult = worker.conn.recv()
            return result
        except (EOFError, OSError):
            pass
    if not worker.proc.is_alive():
        worker.proc.join()
        code = worker.proc.exitcode
        how = f"signal {-code}" if code is not None and code < 0 else f"exit status {code}"
        return failed(spec, f"crashed: the worker process ended ({how})", elapsed)
    if elapsed > timeout:
        worker.proc.kill()
        worker.proc.join()
        return failed(spec, f"timeout: still running after {timeout:g} s", elapsed)
    return None
