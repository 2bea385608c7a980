"""The benchmark runs end to end and reports every figure the benchmark names (values not judged:
timings are reported by the benchmark, never asserted)."""

import importlib.util
import json
import math
import os
import subprocess
import sys
import types
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

# Figures that are one timing less another (the build's control step is the build's time less
# its physics replayed, `other` what the timers did not see): how fast is the benchmark's to
# report (benchmarks/run.py), never a test's to assert.
DIFFERENCES = ("control_us_per_control_step", "breakdown_other_us")


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
        if key not in DIFFERENCES:  # a rate or a count; a difference of two timings is not
            assert figures[key] > 0, key  # bound to be positive on a busy machine
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
    assert "| timed build: the IK, us/step |" in run.stdout
    # The seconds-a-brick targets are the 20-brick pyramid's: not judged on this 2-brick one.
    assert "| simulated s per brick | " in run.stdout and "| not this build |" in run.stdout
    assert "| build / bare |" in run.stdout and "| sweep scaling, 2 workers / 1 |" in run.stdout


def _bench_main():
    """benchmarks/run.py's `main`, loaded in this process."""
    spec = importlib.util.spec_from_file_location("bench_run", ROOT / "benchmarks" / "run.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.main


def _never_measured(*args, **kwargs):
    raise AssertionError("a refused input reached the measurements")


def _refusal(argv: list[str], capsys) -> str:
    """Run the benchmark's `main` in this process expecting a refusal: exit status 2 and one
    error line (an exception escaping `main` fails the test as a traceback would)."""
    try:
        code = _bench_main()(argv)
    except SystemExit as exit_info:  # the parser's own refusals
        code = exit_info.code
    err = capsys.readouterr().err
    assert code == 2, err
    assert len(err.strip().splitlines()) == 1 and err.startswith("benchmarks/run.py: error: ")
    return err


def test_benchmark_refuses_a_word_for_a_number_in_its_parser(capsys, monkeypatch):
    """Refused before perf/figures.py (and MuJoCo with it) is imported: a stub stands there."""
    stub = types.ModuleType("pyramid_sim.perf.figures")
    stub.BenchConfig = stub.run_all = _never_measured
    monkeypatch.setitem(sys.modules, "pyramid_sim.perf.figures", stub)
    assert "layers: 'six' is not a whole number; accepted 1 to 5" in _refusal(
        ["--layers", "six"], capsys
    )


@pytest.mark.physics  # BenchConfig, which checks the ranges, is in perf/figures.py: MuJoCo
@pytest.mark.parametrize(
    "args, named",
    [
        (["--layers", "0"], "layers"),
        (["--frames", "-1"], "frames"),
        (["--sweep-builds", "0"], "sweep builds"),
        (["--sweep-rounds", "11"], "sweep rounds"),
        (["--json", "/proc/no/such/bench.json"], "out"),
    ],
)
def test_benchmark_refuses_bad_input_in_one_line(args, named, capsys, monkeypatch):
    """Out-of-range counts and an unwritable --json, before anything is measured."""
    from pyramid_sim.perf import figures

    monkeypatch.setenv("MUJOCO_GL", os.environ.get("MUJOCO_GL") or "egl")  # main chooses one
    monkeypatch.setattr(figures, "run_all", _never_measured)
    assert named in _refusal(args, capsys)


@pytest.fixture
def clock(monkeypatch):
    """The timers' clock made a counter that only `clock.sleep` moves: exact times, no waiting."""
    from pyramid_sim.perf import timers

    fake = types.SimpleNamespace(now=0.0)
    fake.perf_counter = lambda: fake.now

    def sleep(seconds: float) -> None:
        fake.now += seconds

    fake.sleep = sleep
    monkeypatch.setattr(timers, "time", fake)
    return fake


def test_timed_calls_count_nested_calls_once_and_restore_what_they_wrap(clock):
    from pyramid_sim.perf.timers import timed_calls

    def inner() -> None:
        clock.sleep(0.02)

    def outer() -> None:
        owner.inner()
        clock.sleep(0.02)

    owner = types.SimpleNamespace(inner=inner, outer=outer)
    with timed_calls([(owner, "inner"), (owner, "outer")]) as spent:
        owner.outer()
        owner.inner()
        clock.sleep(1.0)  # between timed calls: not counted
    assert spent[0] == pytest.approx(0.06)  # outer's 0.04 (inner within it once) and inner's
    assert owner.inner is inner and owner.outer is outer


def test_timed_parts_keep_a_clock_each_and_restore_what_they_wrap(clock):
    from pyramid_sim.perf.timers import timed_parts

    def slow() -> None:
        clock.sleep(0.03)

    def quick() -> None:
        clock.sleep(0.01)

    owner = types.SimpleNamespace(slow=slow, quick=quick)
    with timed_parts({"slow": [(owner, "slow")], "quick": [(owner, "quick")]}) as spent:
        owner.slow()
        owner.quick()
        owner.quick()
    assert spent == pytest.approx({"slow": 0.03, "quick": 0.02})
    assert owner.slow is slow and owner.quick is quick


def test_a_build_size_target_is_judged_on_that_build_only():
    from pyramid_sim.perf.targets import DEFAULT_STRUCTURE, TARGETS

    (lockstep,) = [t for t in TARGETS if t.key == "sim_s_per_brick"]
    figures = {"structure": DEFAULT_STRUCTURE, "robot": "panda", "sim_s_per_brick": 12.83}
    assert lockstep.met(figures) is True
    assert lockstep.met({**figures, "sim_s_per_brick": 13.1}) is False
    assert lockstep.met({**figures, "structure": "pyramid-even layers=1"}) is None
    assert lockstep.met({**figures, "robot": "baxter"}) is None
