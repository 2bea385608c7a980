"""On a real terminal (a pseudo-terminal, as a person's shell gives one) the long commands
draw a bar: `evaluate`'s says the episodes done and the time left. Ctrl-C typed there stops
each with one line, exit 130, no traceback and nothing written."""

import os
import pty
import select
import signal
import sys
import time

import pytest

LONG = {  # each far longer than the test waits: Ctrl-C lands while it runs
    "evaluate": ["--policy", "zero", "--layers", "1", "--episodes", "200", "--max-steps", "10"],
    "record": ["--structure", "pyramid", "--layers", "1", "--episodes", "200", "--cameras", "none"],
    "sweep": ["--layers", "1", "--friction", "0.5,0.6,0.7,0.8"],
}
BAR = {  # what the bar shows once the command is under way
    "evaluate": rb"episodes:[^\r\n]*\b2/200 \[\d\d:\d\d<\d\d:\d\d",  # done, [elapsed<left
    "record": rb"episodes:[^\r\n]*\d+/200",
    "sweep": rb"sweep:[^\r\n]*\d/4",
}


def _on_a_terminal(argv, until, seconds=300):
    """Run `pyramid-sim argv` on a pseudo-terminal; once its screen matches `until`, type
    Ctrl-C. Returns (what the screen showed, exit status)."""
    import re

    pid, fd = pty.fork()
    if pid == 0:  # the child: a session of its own, the terminal its controlling one
        signal.signal(signal.SIGINT, signal.SIG_DFL)  # as a shell starts a command
        os.execvp(sys.executable, [sys.executable, "-m", "pyramid_sim.cli", *argv])
    screen, typed, deadline = b"", False, time.monotonic() + seconds
    while time.monotonic() < deadline:
        if select.select([fd], [], [], 0.5)[0]:
            try:
                chunk = os.read(fd, 65536)
            except OSError:  # the child has gone: its side of the terminal closed
                break
            if not chunk:
                break
            screen += chunk
        if not typed and re.search(until, screen):
            os.write(fd, b"\x03")  # Ctrl-C: the terminal sends SIGINT to the command
            typed = True
    else:
        os.kill(pid, signal.SIGKILL)
    os.close(fd)
    _, status = os.waitpid(pid, 0)
    assert typed, screen.decode(errors="replace")[-2000:]
    return screen.decode(errors="replace"), os.waitstatus_to_exitcode(status)


@pytest.mark.parametrize("command", sorted(LONG))
def test_a_terminal_gets_a_bar_and_ctrl_c_ends_in_one_line(command, tmp_path):
    out = tmp_path / "out"
    screen, status = _on_a_terminal([command, *LONG[command], "--out", str(out)], BAR[command])
    assert status == 130, screen[-2000:]
    assert "pyramid-sim: interrupted" in screen and "Traceback" not in screen, screen[-2000:]
    assert not out.exists(), sorted(str(p) for p in out.rglob("*"))
