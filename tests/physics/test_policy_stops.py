"""A policy's own code that exits, is interrupted or fails ends the run as one process ends
it, whatever the workers: `os._exit` in one line with exit status 2 (it ended the run with
status 0 and no word), a KeyboardInterrupt with 130 and no traceback, a failure with 2, and a
SIGTERM landing in act() with 143, the policy not blamed."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
POLICIES = """
import os, time
import numpy as np


def exits(env):
    return lambda observation: os._exit(0)


def interrupts(env):
    def act(observation):
        raise KeyboardInterrupt
    return act


def fails(env):
    def act(observation):
        raise ValueError("broken weights")
    return act


def sleeps(env):
    def act(observation):
        open("acting", "w").close()
        time.sleep(60)
    return act
"""


def _command(tmp_path, *argv):
    (tmp_path / "stop_policies.py").write_text(POLICIES)
    env = {**os.environ, "PYTHONPATH": f"{ROOT / 'src'}{os.pathsep}{tmp_path}"}
    return [sys.executable, "-m", "pyramid_sim.cli", *argv], env


def _run(tmp_path, *argv):
    command, env = _command(tmp_path, *argv)
    return subprocess.run(
        command, capture_output=True, text=True, env=env, cwd=tmp_path, timeout=600
    )


EVALUATE = ["evaluate", "--layers", "1", "--episodes", "2", "--max-steps", "5", "--quiet"]
RECORD = ["record", "--layers", "1", "--episodes", "2", "--cameras", "none", "--quiet"]


@pytest.mark.parametrize("workers", ["1", "2"])
@pytest.mark.parametrize("command", [EVALUATE, RECORD], ids=["evaluate", "record"])
@pytest.mark.parametrize(
    "policy, code, words",
    [
        ("exits", 2, "act() raised SystemExit: called os._exit(0)"),
        ("fails", 2, "act() raised ValueError: broken weights"),
        ("interrupts", 130, "pyramid-sim: interrupted"),
    ],
)
def test_a_policy_that_exits_fails_or_is_interrupted_ends_as_one_process(
    tmp_path, workers, command, policy, code, words
):
    done = _run(
        tmp_path,
        *command,
        "--policy",
        f"stop_policies:{policy}",
        "--workers",
        workers,
        "--out",
        "run",
    )
    assert done.returncode == code, done.stderr
    assert words in done.stderr and "Traceback" not in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1, done.stderr


def test_sigterm_while_act_runs_exits_143_without_blaming_the_policy(tmp_path):
    command, env = _command(tmp_path, *EVALUATE, "--policy", "stop_policies:sleeps", "--out", "run")
    run = subprocess.Popen(command, env=env, cwd=tmp_path, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 300
    while not (tmp_path / "acting").exists() and time.monotonic() < deadline:
        time.sleep(0.1)
    run.send_signal(signal.SIGTERM)
    _, err = run.communicate(timeout=60)
    assert run.returncode == 143, err
    assert err.strip() == "pyramid-sim: terminated"  # the policy not blamed, no traceback
