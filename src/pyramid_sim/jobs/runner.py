"""Jobs spread over worker processes or Ray tasks, each job's end handed back as it comes.

Sweeps (a build per grid point) and recordings (an episode per seed) run here, so both get the
same handling: a job that raises, kills its worker or passes its timeout ends as a failure
naming why, and the others go on; workers run one BLAS thread, set before they import numpy;
on worker processes a job's timeout counts from when its worker is ready (imports done), not
from when it was queued (on Ray, from when it is submitted); and closing the run, or an
interrupt, kills its workers at once. A killed worker runs no cleanup, so worker processes
keep their temporary files in a folder of the run's own, which the run removes as it ends.
"""

from __future__ import annotations

import multiprocessing as mp
import multiprocessing.connection
import os
import shutil
import signal
import sys
import tempfile
import time
from collections import deque
from collections.abc import Callable, Generator, Iterable
from dataclasses import dataclass
from typing import Any

from ..errors import PyramidSimError

# A build is one thread of MuJoCo and small numpy arrays: BLAS pools only spin. Each worker
# gets one BLAS thread, set before it imports numpy (a spawned process inherits the
# environment; a Ray task gets it through its runtime environment).
ONE_BLAS_THREAD = {"OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}


@dataclass(frozen=True)
class JobEnd:
    """How one job ended: its `value` when the work returned, else `failure` says why
    ("crashed: ..." or "timeout: ..."); `wall_s` from when it started."""

    job: Any
    value: Any = None
    failure: str | None = None
    wall_s: float = 0.0


def run_jobs(
    work: Callable[[Any], Any],
    jobs: Iterable[Any],
    *,
    workers: int,
    timeout: float | None = None,
    backend: str = "process",
    address: str | None = None,
    warm: tuple[str, ...] = (),
) -> Generator[JobEnd, None, None]:
    """Each job's end as it comes, `work(job)` run on `workers` spawned processes (which import
    the modules `warm` names before they take a job) or as Ray tasks (on the cluster at
    `address` or a Ray started here). `work` must be picklable: a module-level function or
    an instance of a module-level class. Closing the iterator, or an interrupt, stops every
    worker at once."""
    if backend == "ray":
        return _run_ray(work, list(jobs), workers, timeout, address)
    return _run_processes(work, list(jobs), workers, timeout, warm)


# --- worker processes --------------------------------------------------------------------------


def _die_with_parent() -> None:
    """A worker of a run that was killed stops too, instead of finishing its job unseen."""
    if sys.platform.startswith("linux"):
        import ctypes

        try:
            ctypes.CDLL("libc.so.6").prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
        except (OSError, AttributeError):
            pass


def _worker_loop(
    conn: mp.connection.Connection, work: Callable[[Any], Any], warm: tuple[str, ...]
) -> None:
    _die_with_parent()
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent decides when a run stops
    import importlib

    for module in warm:
        importlib.import_module(module)
    conn.send(("ready", None))
    while True:
        try:
            job = conn.recv()
        except EOFError:
            return
        try:
            conn.send(("done", work(job)))
        except KeyboardInterrupt:  # raised by the job's own code (SIGINT is ignored here)
            conn.send(("interrupted", None))
        except Exception as err:  # the run goes on; the job's end says what happened
            conn.send(("raised", f"{type(err).__name__}: {err}"))


class _Worker:
    """A spawned worker process: starting, ready (idle) or running one job."""

    def __init__(
        self, ctx: Any, work: Callable[[Any], Any], warm: tuple[str, ...], scratch: str
    ) -> None:
        self.conn, child = ctx.Pipe()
        self.proc = ctx.Process(target=_worker_loop, args=(child, work, warm), daemon=True)
        env = {**ONE_BLAS_THREAD, "TMPDIR": scratch}  # tempfile's folders go with the run
        saved = {k: os.environ.get(k) for k in env}
        os.environ.update(env)
        try:
            self.proc.start()
        finally:  # the parent keeps its own settings
            for key, value in saved.items():
                if value is None:
                    os.environ.pop(key, None)
                else:
                    os.environ[key] = value
        child.close()
        self.ready = False
        self.job: Any = None
        self.busy = False
        self.started = 0.0

    def assign(self, job: Any) -> bool:
        """Hand `job` over; False if the worker died while idle (it is replaced)."""
        try:
            self.conn.send(job)
        except (BrokenPipeError, OSError):
            return False
        self.job, self.busy, self.started = job, True, time.monotonic()
        return True

    def end(self, timeout: float | None) -> JobEnd | None:
        """The job's end if it has one now (its value, a crash or a timeout); marks the worker
        ready when it reports so."""
        while self.conn.poll():
            try:
                kind, payload = self.conn.recv()
            except (EOFError, OSError):
                break
            if kind == "ready":
                self.ready = True
                continue
            if kind == "interrupted":  # a job's Ctrl-C stops the run, as in one process
                raise KeyboardInterrupt
            return self._finish(
                payload if kind == "done" else None,
                None if kind == "done" else f"crashed: {payload}",
            )
        if not self.proc.is_alive():
            self.proc.join()
            code = self.proc.exitcode
            if not self.ready:  # its imports failed: every worker would, so the run stops
                raise PyramidSimError(f"a worker process failed to start (exit status {code})")
            if not self.busy:  # died idle: replaced, no job lost
                return None
            how = f"signal {-code}" if code is not None and code < 0 else f"exit status {code}"
            return self._finish(None, f"crashed: the worker process ended ({how})")
        if self.busy and timeout is not None and time.monotonic() - self.started > timeout:
            self.stop()
            return self._finish(None, f"timeout: still running after {timeout:g} s")
        return None

    def _finish(self, value: Any, failure: str | None) -> JobEnd:
        end = JobEnd(self.job, value, failure, time.monotonic() - self.started)
        self.job, self.busy = None, False
        return end

    def stop(self) -> None:
        if self.proc.is_alive():
            self.proc.kill()
        self.proc.join()
        self.conn.close()


def _run_processes(
    work: Callable[[Any], Any],
    jobs: list[Any],
    workers: int,
    timeout: float | None,
    warm: tuple[str, ...],
) -> Generator[JobEnd, None, None]:
    ctx = mp.get_context("spawn")  # no GL or MuJoCo state forked
    pending = deque(jobs)
    pool: list[_Worker] = []
    scratch = tempfile.mkdtemp(prefix="pyramid-sim-workers-")
    try:
        while pending or any(w.busy for w in pool):
            while len(pool) < min(workers, len(pending) + sum(w.busy for w in pool)):
                pool.append(_Worker(ctx, work, warm, scratch))
            for worker in pool:
                if worker.ready and not worker.busy and pending:
                    job = pending.popleft()
                    if not worker.assign(job):
                        pending.appendleft(job)
            deadlines = [w.started + timeout for w in pool if w.busy and timeout is not None]
            wait = max(0.0, min(deadlines) - time.monotonic()) if deadlines else None
            waitables = [w.conn for w in pool] + [w.proc.sentinel for w in pool]
            mp.connection.wait(waitables, timeout=wait)
            for worker in list(pool):
                end = worker.end(timeout)
                # Crashed or timed out, its job's end taken (one that dies after `end` looked
                # still holds its job: the next pass reports it): replaced when needed.
                if not worker.busy and not worker.proc.is_alive():
                    worker.stop()
                    pool.remove(worker)
                if end is not None:
                    yield end
    finally:
        for worker in pool:
            worker.stop()
        shutil.rmtree(scratch, ignore_errors=True)  # what killed workers could not remove


# --- Ray tasks ----------------------------------------------------------------------------------


def _call(work: Callable[[Any], Any], job: Any) -> Any:
    """A Ray task (Ray's logs name every one `_call`): `work` may be any picklable callable,
    Ray's decorator wants a function."""
    return work(job)


def _ray_reason(err: Exception) -> str:
    """What went wrong in a Ray task, as the process backend says it (a task's own exception
    is its `cause`; Ray's message starts with a header naming the task)."""
    cause = getattr(err, "cause", None)
    if isinstance(cause, Exception):
        return f"{type(cause).__name__}: {cause}"
    return f"{type(err).__name__}: {(str(err).splitlines() or [''])[0]}"


def _run_ray(
    work: Callable[[Any], Any],
    jobs: list[Any],
    workers: int,
    timeout: float | None,
    address: str | None,
) -> Generator[JobEnd, None, None]:
    """At most `workers` tasks at once. A task's clock starts when it is submitted: Ray starts
    its worker processes itself, and the first task on each pays for the process and its
    imports (worker processes here start the clock once their imports are done)."""
    from .ray_session import ray_session

    with ray_session(address, workers) as ray:
        task = ray.remote(
            num_cpus=1, max_retries=0, runtime_env={"env_vars": dict(ONE_BLAS_THREAD)}
        )(_call)
        pending = deque(jobs)
        running: dict[Any, tuple[Any, float]] = {}
        try:
            while pending or running:
                while pending and len(running) < workers:
                    job = pending.popleft()
                    running[task.remote(work, job)] = (job, time.monotonic())
                starts = [start for _, start in running.values()]
                wait = None if timeout is None else min(starts) + timeout - time.monotonic()
                ready, _ = ray.wait(
                    list(running), num_returns=1, timeout=None if wait is None else max(0.0, wait)
                )
                for ref in ready:
                    job, start = running.pop(ref)
                    try:
                        end = JobEnd(job, ray.get(ref), None, time.monotonic() - start)
                    except ray.exceptions.RayError as err:
                        reason = f"crashed: {_ray_reason(err)}"
                        end = JobEnd(job, None, reason, time.monotonic() - start)
                    yield end
                for ref, (job, start) in list(running.items()):
                    if timeout is not None and time.monotonic() - start > timeout:
                        ray.cancel(ref, force=True)
                        del running[ref]
                        reason = f"timeout: still running after {timeout:g} s"
                        yield JobEnd(job, None, reason, time.monotonic() - start)
        finally:
            for ref in running:
                ray.cancel(ref, force=True)
