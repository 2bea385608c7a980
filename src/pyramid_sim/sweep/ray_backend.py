"""The Ray backend of a sweep: the same runs as Ray tasks, on a local Ray instance or a
cluster, and the one line a cluster that refuses us gets."""

from __future__ import annotations

import contextlib
import os
import sys
import tempfile
import time
from collections import deque
from collections.abc import Iterable, Iterator
from typing import Any

from ..errors import PyramidSimError
from .backends import OnResult, failed, run_one
from .grid import SweepRun


def ray_connection_advice(address: str | None, err: Exception) -> str:
    """Why a Ray cluster refused us, with what to set: clusters started with `ray start` (Ray
    2.60 and later) ask clients for a token, and a client without `RAY_AUTH_MODE=token` only
    hears 'Failed to connect' after about 20 s."""
    advice = (
        f"cannot connect to the Ray cluster at {address} ({str(err).splitlines()[0]}); "
        "a cluster started with `ray start` wants token authentication: set RAY_AUTH_MODE=token "
        "for the sweep (the token is in ~/.ray/auth_token where the head node was started; "
        "elsewhere set RAY_AUTH_TOKEN to it)"
    )
    if os.environ.get("RAY_AUTH_MODE") == "token":
        advice = (
            f"cannot connect to the Ray cluster at {address} ({str(err).splitlines()[0]}) "
            "with RAY_AUTH_MODE=token: check the address and that RAY_AUTH_TOKEN or "
            "~/.ray/auth_token holds the head node's token"
        )
    return advice


@contextlib.contextmanager
def native_stderr_held(hold: bool) -> Iterator[None]:
    """Ray's C++ core writes a warning a second to stderr while a cluster refuses it (about
    20): held back, a refusal (ConnectionError) reads as the one line that says what to set.
    On success or another error they are passed on."""
    if not hold:
        yield
        return
    sys.stderr.flush()
    saved = os.dup(2)
    with tempfile.TemporaryFile() as held:
        os.dup2(held.fileno(), 2)
        refused = False
        try:
            yield
        except ConnectionError:
            refused = True
            raise
        finally:
            os.dup2(saved, 2)
            os.close(saved)
            if not refused:
                held.seek(0)
                sys.stderr.write(held.read().decode(errors="replace"))


@contextlib.contextmanager
def ray_session(address: str | None, workers: int) -> Iterator[Any]:
    """The `ray` module, connected: to the cluster at `address`, or to a local instance started
    here with `workers` CPUs (and shut down on leaving), or to the one already running."""
    import logging

    import ray

    started_here = not ray.is_initialized()
    if started_here:
        try:
            with native_stderr_held(address is not None):
                ray.init(
                    address=address,
                    num_cpus=None if address else workers,
                    include_dashboard=False,
                    log_to_driver=False,
                    logging_level=logging.ERROR,
                )
        except ConnectionError as err:
            raise PyramidSimError(ray_connection_advice(address, err)) from None
    try:
        yield ray
    finally:
        if started_here:
            ray.shutdown()


def run_ray(
    specs: Iterable[SweepRun],
    workers: int,
    timeout: float,
    on_result: OnResult,
    address: str | None = None,
) -> None:
    """Run every spec as a Ray task, at most `workers` at once, on a local Ray instance (started
    with `workers` CPUs) or the cluster at `address`; the nodes need pyramid_sim installed."""
    with ray_session(address, workers) as ray:
        task = ray.remote(num_cpus=1, max_retries=0)(run_one)
        pending = deque(specs)
        running: dict[Any, tuple[SweepRun, float]] = {}
        try:
            while pending or running:
                while pending and len(running) < workers:
                    spec = pending.popleft()
                    running[task.remote(spec)] = (spec, time.monotonic())
                wait = min(start + timeout for _, start in running.values()) - time.monotonic()
                ready, _ = ray.wait(list(running), num_returns=1, timeout=max(0.0, wait))
                for ref in ready:
                    spec, start = running.pop(ref)
                    try:
                        on_result(ray.get(ref))
                    except ray.exceptions.RayError as err:
                        reason = f"crashed: {type(err).__name__}: {str(err).splitlines()[0]}"
                        on_result(failed(spec, reason, time.monotonic() - start))
                for ref, (spec, start) in list(running.items()):
                    if time.monotonic() - start > timeout:
                        ray.cancel(ref, force=True)
                        del running[ref]
                        reason = f"timeout: still running after {timeout:g} s"
                        on_result(failed(spec, reason, timeout))
        finally:
            for ref in running:
                ray.cancel(ref, force=True)
