"""The job runner sweeps and recordings share: crashes, exceptions and timeouts end a job as a
failure naming why, the timeout counts from when the worker is ready, workers run one BLAS
thread, and closing the run stops every worker at once."""

from __future__ import annotations

import multiprocessing
import os
import time

import pytest

from pyramid_sim.errors import PyramidSimError
from pyramid_sim.jobs.runner import run_jobs

pytestmark = pytest.mark.processes


# Stand-ins for a job, run in spawned workers (importable by name from this module).
def _work(job: int) -> dict:
    if job == 1:
        os._exit(3)
    if job == 2:
        time.sleep(60)
    if job == 3:
        raise ValueError("no such brick")
    return {"job": job, "pid": os.getpid(), "blas": _blas_threads()}


def _blas_threads() -> int:
    """The threads numpy's OpenBLAS runs, asked of the library itself."""
    import ctypes

    import numpy  # noqa: F401  loads OpenBLAS

    with open("/proc/self/maps") as maps:
        library = sorted({line.split()[-1] for line in maps if "openblas" in line.lower()})[0]
    blas = ctypes.CDLL(library)
    for name in ("scipy_openblas_get_num_threads64_", "openblas_get_num_threads"):
        if hasattr(blas, name):
            return int(getattr(blas, name)())
    raise AssertionError(f"{library} tells no thread count")


def _temp_then_sleepy(job: float) -> str:
    """Make a temporary folder, as an episode's film does, and sleep in it."""
    import tempfile

    folder = tempfile.mkdtemp(prefix="pyramid-sim-test-")
    time.sleep(job)
    return folder


def _sleepy(job: int) -> int:
    time.sleep(job)
    return os.getpid()


def _sleepy_then_marked(job: tuple[float, str]) -> int:
    """Sleep, then leave a file saying the job ran to its end."""
    time.sleep(job[0])
    with open(job[1], "w") as mark:
        mark.write("done")
    return os.getpid()


def test_crashes_exceptions_and_timeouts_end_as_failures_and_the_others_go_on():
    ends = {e.job: e for e in run_jobs(_work, [0, 1, 2, 3, 4], workers=2, timeout=2.0)}
    assert sorted(ends) == [0, 1, 2, 3, 4]
    assert ends[0].failure is None and ends[0].value["job"] == 0
    assert ends[4].value["job"] == 4
    assert ends[1].value is None
    assert ends[1].failure == "crashed: the worker process ended (exit status 3)"
    assert ends[2].failure == "timeout: still running after 2 s"
    assert ends[3].failure == "crashed: ValueError: no such brick"


def test_workers_run_one_blas_thread_and_the_parent_keeps_its_own(monkeypatch):
    monkeypatch.delenv("OPENBLAS_NUM_THREADS", raising=False)
    (end,) = run_jobs(_work, [0], workers=1)
    assert end.value["blas"] == 1  # OpenBLAS itself, which took 2 when set after numpy loaded
    assert end.value["pid"] != os.getpid()
    assert "OPENBLAS_NUM_THREADS" not in os.environ


def test_the_timeout_counts_from_when_the_worker_is_ready(tmp_path, monkeypatch):
    """A worker whose imports take 3 s still has its whole 2 s for a job of 0.5 s."""
    (tmp_path / "slow_import_for_runner.py").write_text("import time\ntime.sleep(3)\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    ends = list(run_jobs(_sleepy, [0.5], workers=1, timeout=2.0, warm=("slow_import_for_runner",)))
    assert ends[0].failure is None  # counted from the import's start, it would have timed out


def test_a_worker_that_cannot_start_is_one_error_not_an_endless_respawn():
    with pytest.raises(PyramidSimError, match="failed to start"):
        list(run_jobs(_work, [0], workers=1, warm=("no_such_module_anywhere",)))


def test_closing_the_run_stops_every_worker_at_once(tmp_path):
    """Stopped, not waited for: the jobs still sleeping never reach their end."""
    marks = [tmp_path / f"job{k}" for k in range(3)]
    jobs = [(seconds, str(mark)) for seconds, mark in zip((0.0, 60.0, 60.0), marks)]
    ends = run_jobs(_sleepy_then_marked, jobs, workers=2)
    first = next(ends)
    pid = first.value
    ends.close()  # as an interrupt in the caller's loop does
    with pytest.raises(ProcessLookupError):
        os.kill(pid, 0)
    assert multiprocessing.active_children() == []  # the two still sleeping are gone too
    assert [m.exists() for m in marks] == [True, False, False]  # killed, not waited for


def test_a_killed_workers_temporary_files_go_with_its_run():
    """A worker killed mid-job runs no cleanup: its temporary folders sit in one of the run's
    own, which the run removes, and none lands in the machine's temporary folder."""
    ends = run_jobs(_temp_then_sleepy, [0.0, 60.0], workers=2)
    first = next(ends).value
    scratch = os.path.dirname(first)
    assert os.path.basename(scratch).startswith("pyramid-sim-workers-")
    assert os.path.isdir(scratch)  # the other worker still sleeps in it
    ends.close()
    assert not os.path.exists(scratch) and not os.path.exists(first)


def test_a_ray_tasks_failure_reads_as_the_process_backends():
    from pyramid_sim.jobs.runner import _ray_reason

    class TaskError(Exception):
        cause = ValueError("no such brick")

    assert _ray_reason(TaskError("ray::_call() (pid=7, ip=1.2.3.4)\n  ...")) == (
        "ValueError: no such brick"
    )
    assert _ray_reason(RuntimeError("")) == "RuntimeError: "
