"""A policy's own code (its factory, reset() and act()) called so that whatever it does wrong
ends in one line naming it: an exception, a `sys.exit`, and an `os._exit`, which would end
the whole run at once with no word (and with exit status 0). A Ctrl-C or a SIGTERM that lands
while it runs is the user's stop, not the policy's failure, and passes through."""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

from ...errors import ActionError, PolicyError, Terminated


@contextmanager
def exits_raised() -> Iterator[None]:
    """Within the block, `os._exit(n)` raises SystemExit naming the call instead of ending
    the process unseen; the real one is back after."""
    real = os._exit

    def raised(status: int) -> None:
        raise SystemExit(f"called os._exit({status})")

    os._exit = raised  # type: ignore[assignment]
    try:
        yield
    finally:
        os._exit = real


def policy_call(method: Callable[..., Any], what: str, *args: Any) -> Any:
    """`method(*args)` of a policy; PolicyError "`what` raised <kind>: <message>" for anything
    it raises or any exit it makes (a PolicyError or ActionError of ours passes as it is, and
    so do SIGTERM's exit and Ctrl-C)."""
    try:
        with exits_raised():
            return method(*args)
    except (ActionError, PolicyError, Terminated):
        raise
    except (Exception, SystemExit) as err:  # the user's code: one line naming it
        raise PolicyError(f"{what} raised {type(err).__name__}: {err}") from err
