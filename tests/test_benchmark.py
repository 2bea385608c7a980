"""The benchmark runs end to end and reports every figure the benchmark names (values not judged:
timings are reported by the benchmark, never asserted)."""

import json
import math
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
KEYS = (
    "env_steps_per_s",
    "env_to_build_ratio",
    "record_to_build_ratio",
    "record_frames_per_s",
    "bare_steps_per_s",
    "build_steps_per_s",
    "build_to_bare_ratio",
    "ik_solve_ms_median",
    "ik_solve_ms_p99",
    "render_ms_per_frame_shadows",
    "render_ms_per_frame_no_shadows",
    "encode_ms_per_frame",
    "sim_s_per_brick",
    "bricks_per_hour_sim",
    "peak_rss_mb",
    "sweep_builds_per_hour_1",
    "sweep_builds_per_hour_2",
    "sweep_scaling",
    "physics_us_per_control_step",
    "control_us_per_control_step",
    "control_budget_us",
    "ik_floor_us_per_control_step",
    "breakdown_scheduling_us",
    "breakdown_ik_us",
    "breakdown_custody_us",
    "breakdown_monitors_us",
    "breakdown_physics_us",
    "breakdown_other_us",
)


def _bench(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "run.py"), *args],
        capture_output=True,
        text=True,
        timeout=600,
    )


@pytest.mark.physics
def test_benchmark_reports_every_figure(tmp_path):
    out = tmp_path / "bench.json"
    run = _bench(
        "--layers",
        "1",
        "--frames",
        "3",
        "--sweep-builds",
        "1",
        "--sweep-rounds",
        "1",
        "--json",
        str(out),
    )
    assert run.returncode == 0, run.stderr
    figures = json.loads(out.read_text())
    for key in KEYS:
        assert isinstance(figures[key], (int, float)) and math.isfinite(figures[key]), key
        assert figures[key] > 0, key
    # The 2-brick build succeeded, in the build and in every sweep run, and replaying its
    # recorded controls alone reproduced it bit for bit (so the replay rate is its physics).
    assert figures["build_success"] and figures["bricks_placed"] == 2
    assert figures["sweep_successes_1"] == 1 and figures["sweep_successes_2"] == 2
    assert figures["replay_matches_build"] is True
    # 100 Hz control, 500 Hz physics, one IK solve a control step at the default interval
    control_steps = figures["build_physics_steps"] / 5
    assert figures["ik_solves"] == control_steps
    assert figures["ik_solves_per_control_step"] == pytest.approx(
        figures["ik_solves"] / control_steps
    )
    # The IK's floor is part of the control step it is measured against.
    assert figures["ik_floor_us_per_control_step"] < figures["control_us_per_control_step"]
    assert figures["ik_floor_us_per_control_step"] < figures["breakdown_ik_us"]
    assert "| timed build: the IK, us/step |" in run.stdout
    # The seconds-a-brick targets are the 20-brick pyramid's: not judged on this 2-brick one.
    assert "| simulated s per brick | " in run.stdout and "| not this build |" in run.stdout
    assert "| build / bare |" in run.stdout and "| sweep scaling, 2 workers / 1 |" in run.stdout


@pytest.mark.parametrize(
    "args, named",
    [
        (["--layers", "0"], "layers"),
        (["--layers", "six"], "layers"),
        (["--frames", "-1"], "frames"),
        (["--sweep-builds", "0"], "sweep builds"),
        (["--sweep-rounds", "11"], "sweep rounds"),
        (["--json", "/proc/no/such/bench.json"], "out"),
    ],
)
def test_benchmark_refuses_bad_input_in_one_line(args, named, tmp_path):
    run = _bench(*args)
    assert run.returncode == 2
    assert len(run.stderr.strip().splitlines()) == 1 and named in run.stderr
    assert "Traceback" not in run.stderr


def test_timed_calls_count_nested_calls_once_and_restore_what_they_wrap():
    import time
    from types import SimpleNamespace

    from pyramid_sim.perf.timers import timed_calls

    def inner() -> None:
        time.sleep(0.02)

    def outer() -> None:
        owner.inner()
        time.sleep(0.02)

    owner = SimpleNamespace(inner=inner, outer=outer)
    with timed_calls([(owner, "inner"), (owner, "outer")]) as spent:
        owner.outer()
        owner.inner()
    assert 0.06 <= spent[0] < 0.2  # outer's 0.04 (inner within it once) and inner's 0.02
    assert owner.inner is inner and owner.outer is outer


def test_timed_parts_keep_a_clock_each_and_restore_what_they_wrap():
    import time
    from types import SimpleNamespace

    from pyramid_sim.perf.timers import timed_parts

    def slow() -> None:
        time.sleep(0.03)

    def quick() -> None:
        time.sleep(0.01)

    owner = SimpleNamespace(slow=slow, quick=quick)
    with timed_parts({"slow": [(owner, "slow")], "quick": [(owner, "quick")]}) as spent:
        owner.slow()
        owner.quick()
        owner.quick()
    assert 0.03 <= spent["slow"] < 0.1 and 0.02 <= spent["quick"] < 0.08
    assert owner.slow is slow and owner.quick is quick


def test_a_build_size_target_is_judged_on_that_build_only():
    from pyramid_sim.perf.targets import DEFAULT_STRUCTURE, TARGETS

    (lockstep,) = [t for t in TARGETS if t.key == "sim_s_per_brick"]
    figures = {"structure": DEFAULT_STRUCTURE, "robot": "panda", "sim_s_per_brick": 12.83}
    assert lockstep.met(figures) is True
    assert lockstep.met({**figures, "sim_s_per_brick": 13.1}) is False
    assert lockstep.met({**figures, "structure": "pyramid-even layers=1"}) is None
    assert lockstep.met({**figures, "robot": "baxter"}) is None
