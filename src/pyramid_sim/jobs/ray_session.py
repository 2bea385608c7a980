"""A Ray session for the runner's Ray backend: a local Ray instance or a cluster, and the one
line a cluster that refuses us gets."""

from __future__ import annotations

import contextlib
import os
import sys
import tempfile
from collections.abc import Iterator
from typing import Any

from ..errors import PyramidSimError


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
