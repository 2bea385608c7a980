"""How a command ends, the same for `pyramid-sim` and the benchmark's scripts: a refusal in
one line with exit status 2, a failure in one line with 1, Ctrl-C with 130 and SIGTERM with
143, none with a traceback (the files a run leaves are whole or gone either way)."""

from __future__ import annotations

import ctypes
import signal
import sys
import threading
from collections.abc import Callable
from typing import NoReturn

from ..errors import ConfigError, MachineError, PyramidSimError, Terminated

EXIT_USAGE = 2  # bad input: nothing ran (argparse's own status)
EXIT_FAILED = 1  # the run failed
EXIT_INTERRUPTED = 130  # as a shell reports a process ended by SIGINT


def _exit_on_sigterm(signum: int, frame: object) -> NoReturn:
    raise Terminated(128 + signum)


def ended(prog: str, run: Callable[[], int]) -> int:
    """`run()`'s exit status, or the one line and status of how it ended otherwise. SIGTERM
    unwinds like Ctrl-C (by default it ends Python without running any `finally`, and a
    temporary file would stay)."""
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGTERM, _exit_on_sigterm)
    try:
        return run()
    except (ConfigError, MachineError) as err:  # refused before anything ran
        print(f"{prog}: error: {err}", file=sys.stderr)
        return EXIT_USAGE
    except (PyramidSimError, OSError) as err:
        print(f"{prog}: failed: {err}", file=sys.stderr)
        return EXIT_FAILED
    except KeyboardInterrupt:  # Ctrl-C: partial files are already gone; no traceback
        print(f"{prog}: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except Terminated as end:  # SIGTERM: said as Ctrl-C is, so a log tells why it stopped
        print(f"{prog}: terminated", file=sys.stderr)
        return int(end.code or 128 + signal.SIGTERM)
    except ctypes.ArgumentError as err:
        if not interrupted(err):
            raise
        print(f"{prog}: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED


def interrupted(err: ctypes.ArgumentError) -> bool:
    """Whether ctypes' error wraps a Ctrl-C: one that lands while a frame renders arrives as
    "argument 1: KeyboardInterrupt" from the OpenGL binding's argument conversion."""
    cause = err.__cause__ or err.__context__
    return isinstance(cause, KeyboardInterrupt) or "KeyboardInterrupt" in str(err)
