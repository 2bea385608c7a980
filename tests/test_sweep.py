"""Sweeps: grids, the resumable CSV, the worker pool's failure rows, the map, and both backends."""

from __future__ import annotations

import csv
import math
import os
import re
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest

from pyramid_sim.errors import ConfigError
from pyramid_sim.sweep.grid import SweepConfig, parse_axis
from pyramid_sim.sweep.heatmaps import write_heatmaps
from pyramid_sim.sweep.report import grid_rows, summary_table
from pyramid_sim.sweep.runs import RunResult, make_row, run_builds
from pyramid_sim.sweep.store import COLUMNS, SweepRow, SweepStore


def test_range_and_list_grids():
    assert parse_axis("friction", "0.3:1.5:5").values == (0.3, 0.6, 0.9, 1.2, 1.5)
    assert parse_axis("brick_mass", "0.5, 1,2").values == (0.5, 1.0, 2.0)
    assert parse_axis("grip_force", "20:20:1").values == (20.0,)


@pytest.mark.parametrize(
    "name, text, words",
    [
        ("friction", "0.3:1.5:0", "0 points"),
        ("friction", "0.3:1.5", "cannot read"),
        ("brick_mass", "-0.5,1", "brick mass"),
        ("brick_mass", "abc", "cannot read"),
        ("grip_force", "nan", "grip force"),
        ("pad_friction", "1,1", "repeated"),
        ("friction", "0.3:1.5:51", "51 points"),
    ],
)
def test_bad_grids_are_refused_naming_the_parameter(name, text, words):
    with pytest.raises(ConfigError, match=words):
        parse_axis(name, text)


def test_the_grid_holds_every_point_and_repeat_once():
    config = SweepConfig(
        axes=(parse_axis("friction", "0.5,1"), parse_axis("brick_mass", "0.2:1.0:3")), repeats=2
    )
    runs = config.runs()
    assert len(runs) == 2 * 3 * 2
    assert len({r.key() for r in runs}) == len(runs)
    assert {r.seed for r in runs} == {0, 1}
    x, y = config.plot_axes()
    assert (x.name, y.name) == ("friction", "brick_mass")
    assert runs[0].config().brick.friction == 0.5 and runs[-1].config().brick.mass == 1.0


@pytest.mark.parametrize(
    "args, words",
    [
        (["--friction", "0.3:1.5:0"], "friction"),
        (["--brick-mass=-0.2,1"], "brick mass"),
        (["--stiffness", "1,2"], "unrecognized"),
        (["--workers", "0"], "workers"),
        (["--timeout", "0"], "timeout"),
        (["--repeats", "1000"], "repeats"),
        (["--ray-address", "auto"], "ray address"),
        (["--spawn-jitter", "-1"], "spawn jitter"),
    ],
)
def test_bad_sweep_options_are_one_line_and_exit_2(tmp_path, refused, args, words):
    out = tmp_path / "sweep"
    assert words in refused(["sweep", *args, "--out", str(out)])
    assert not out.exists()


def _spec_rows(config: SweepConfig) -> list[dict]:
    return [make_row(spec, 1.0, None, success=True, bricks_placed=1) for spec in config.runs()]


def test_the_csv_survives_a_torn_last_line_and_keeps_one_row_per_run(tmp_path):
    config = SweepConfig(axes=(parse_axis("friction", "0.5,1,1.5"),))
    rows = _spec_rows(config)
    store = SweepStore(tmp_path / "sweep.csv")
    store.append(rows[0])
    store.append(rows[1])
    with open(tmp_path / "sweep.csv", "a") as f:
        f.write("pyramid-even,4,1.5,0.5,20")  # killed in the middle of a row
    again = SweepStore(tmp_path / "sweep.csv")
    assert len(again.rows) == 2
    again.append(rows[2])
    with open(tmp_path / "sweep.csv") as f:
        table = list(csv.DictReader(f))
    assert [r["friction"] for r in table] == ["0.5", "1.0", "1.5"]
    assert tuple(table[0]) == COLUMNS


def test_a_retried_run_is_run_again_and_its_later_row_stands(tmp_path):
    config = SweepConfig(axes=(parse_axis("friction", "0.5,1"),))
    rows = _spec_rows(config)
    failed = {**rows[0], "success": False, "failure_reason": "timeout: still running after 1 s"}
    store = SweepStore(tmp_path / "sweep.csv")
    store.append(failed)
    store.append(rows[1])
    keys = [spec.key() for spec in config.runs()]
    assert store.done() == set(keys)  # resumed as it was: nothing runs again
    assert store.done(retry_failed=True) == {keys[1]}  # the timed-out point runs again
    store.append(rows[0])
    for again in (store, SweepStore(tmp_path / "sweep.csv")):
        assert [(r["friction"], r.success) for r in again.rows] == [("1.0", True), ("0.5", True)]
    assert len((tmp_path / "sweep.csv").read_text().splitlines()) == 4  # the failure kept


# Stand-ins for a build, run in spawned workers: seed 0 finishes, 1 kills its process, 2 hangs.
def _fake_run(spec):
    if spec.seed == 1:
        os._exit(3)
    if spec.seed == 2:
        time.sleep(60)
    return RunResult(spec, make_row(spec, 0.0, None, success=True))


@pytest.mark.processes
def test_the_pool_turns_crashes_and_timeouts_into_failed_rows_and_goes_on():
    config = SweepConfig(axes=(parse_axis("friction", "0.5,1"),), repeats=3)
    results: list[RunResult] = []
    run_builds(config.runs(), workers=2, timeout=3.0, on_result=results.append, run=_fake_run)
    assert sorted(r.spec.key() for r in results) == sorted(s.key() for s in config.runs())
    by_seed = {}
    for r in results:
        by_seed.setdefault(r.spec.seed, []).append(r.row)
    assert all(row["success"] and row["failure_reason"] is None for row in by_seed[0])
    assert all(
        "crashed" in row["failure_reason"] and "exit status 3" in row["failure_reason"]
        for row in by_seed[1]
    )
    assert all("timeout" in row["failure_reason"] for row in by_seed[2])


def test_the_map_and_summary_show_success_and_the_envelope_edge(tmp_path):
    config = SweepConfig(axes=(parse_axis("friction", "0.5,1"), parse_axis("brick_mass", "0.5,3")))
    rows = []
    for spec in config.runs():
        heavy = spec.config().brick.mass > 1
        rows.append(
            SweepRow.of(
                make_row(
                    spec,
                    1.0,
                    "dropped" if heavy else None,
                    success=not heavy,
                    worst_error_xy_mm=math.inf if heavy else 1.5,
                    max_slip_mm=40.0 if heavy else 0.8,
                )
            )
        )
    table = summary_table(rows, config)
    assert table.count("1/1") == 2 and table.count("0/1") == 2 and "not placed" in table
    write_heatmaps(rows, config, tmp_path / "sweep.png")
    assert (tmp_path / "sweep.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def _sweep_cmd(out: Path, *extra: str) -> list[str]:
    return [
        sys.executable,
        "-m",
        "pyramid_sim.cli",
        "sweep",
        "--structure",
        "pyramid",
        "--layers",
        "1",
        "--out",
        str(out),
        "--quiet",
        *extra,
    ]


def _csv_rows(path: Path) -> list[dict]:
    with open(path) as f:
        return list(csv.DictReader(f))


@pytest.mark.physics
def test_a_killed_sweep_resumes_to_exactly_one_row_per_run(tmp_path):
    out = tmp_path / "s"
    cmd = _sweep_cmd(out, "--brick-mass", "0.4,0.5,0.6,0.7", "--workers", "1")
    # A killed run cleans nothing: its workers' temporary folder stays in this test's.
    env = {**os.environ, "TMPDIR": str(tmp_path)}
    proc = subprocess.Popen(cmd, start_new_session=True, stdout=subprocess.DEVNULL, env=env)
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        if (out / "sweep.csv").exists() and len(_csv_rows(out / "sweep.csv")) >= 1:
            break
        time.sleep(0.2)
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()
    first = _csv_rows(out / "sweep.csv")
    assert 1 <= len(first) < 4, "the kill should land half way"
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    rows = _csv_rows(out / "sweep.csv")
    assert sorted(r["brick_mass"] for r in rows) == ["0.4", "0.5", "0.6", "0.7"]
    assert rows[: len(first)] == first  # nothing lost or rewritten
    assert all(r["success"] == "true" for r in rows)
    assert (out / "sweep.png").exists()


@pytest.mark.physics
@pytest.mark.slow  # starts a local Ray instance
@pytest.mark.xdist_group("ray")  # one Ray at a time under pytest-xdist (.ci/run)
def test_ray_gives_the_same_rows_as_processes(tmp_path):
    """The local Ray instance writes its token under HOME and its session under RAY_TMPDIR:
    both are this test's own folders (the session's sockets need a short path)."""
    grid = ["--grip-force", "1,20", "--workers", "2"]
    env = {k: v for k, v in os.environ.items() if not k.startswith("RAY_")}
    env.update(HOME=str(tmp_path / "home"), RAY_USAGE_STATS_ENABLED="0")
    with tempfile.TemporaryDirectory(prefix="ray", dir="/tmp") as ray_tmp:
        env["RAY_TMPDIR"] = ray_tmp
        for backend in ("process", "ray"):
            done = subprocess.run(
                _sweep_cmd(tmp_path / backend, *grid, "--backend", backend),
                capture_output=True,
                text=True,
                timeout=600,
                env=env,
            )
            assert done.returncode == 0, done.stderr
    rows = {}
    for backend in ("process", "ray"):
        table = _csv_rows(tmp_path / backend / "sweep.csv")
        rows[backend] = sorted(
            ({k: v for k, v in r.items() if k != "wall_time_s"} for r in table),
            key=lambda r: float(r["grip_force"]),
        )
    assert len(rows["ray"]) == 2
    assert rows["ray"] == rows["process"]
    assert [r["success"] for r in rows["ray"]] == ["false", "true"]  # outcomes differ: 1 N drops


def test_a_grip_by_mass_map_carries_the_coulomb_limit(tmp_path):
    """2 mu F / g: 20 N a pad at pad friction 1 holds 4.08 kg at rest; the map with grip
    force and brick mass on its axes draws that line over the cells."""
    from pyramid_sim.sweep.heatmaps import coulomb_mass_limit

    assert coulomb_mass_limit(20.0, 1.0) == pytest.approx(4.077, abs=1e-3)
    config = SweepConfig(
        axes=(parse_axis("grip_force", "2:20:3"), parse_axis("brick_mass", "0.5,1"))
    )
    rows = [SweepRow.of(row) for row in _spec_rows(config)]
    write_heatmaps(rows, config, tmp_path / "map.png")
    assert (tmp_path / "map.png").stat().st_size > 10_000


def test_a_refused_ray_connection_says_what_to_set(monkeypatch):
    from pyramid_sim.jobs.ray_session import ray_connection_advice

    monkeypatch.delenv("RAY_AUTH_MODE", raising=False)
    text = ray_connection_advice(
        "127.0.0.1:6390", ConnectionError("Failed to connect to Ray cluster")
    )
    assert "127.0.0.1:6390" in text and "set RAY_AUTH_MODE=token" in text
    monkeypatch.setenv("RAY_AUTH_MODE", "token")
    text = ray_connection_advice("127.0.0.1:6390", ConnectionError("Failed to connect"))
    assert "with RAY_AUTH_MODE=token" in text and "RAY_AUTH_TOKEN" in text


@pytest.mark.physics
def test_a_sweep_folder_compares_the_two_schedules(tmp_path):
    """The same grid swept with each schedule into one folder: the CSV keys its rows by
    schedule, so both are kept side by side, and the overlap schedule's bricks come faster."""
    out = tmp_path / "both"
    grid = ["--structure", "pyramid-even", "--layers", "2", "--friction", "0.8", "--workers", "2"]
    for schedule in ("lockstep", "overlap"):
        cmd = [
            sys.executable,
            "-m",
            "pyramid_sim.cli",
            "sweep",
            "--out",
            str(out),
            "--quiet",
            *grid,
            "--schedule",
            schedule,
        ]
        done = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
        assert done.returncode == 0, done.stderr
    rows = {r["schedule"]: r for r in _csv_rows(out / "sweep.csv")}
    assert set(rows) == {"lockstep", "overlap"}
    assert all(r["success"] == "true" for r in rows.values())
    assert float(rows["overlap"]["sim_time_s"]) < 0.75 * float(rows["lockstep"]["sim_time_s"])


@pytest.mark.parametrize(
    "raised, shown", [(None, True), (ConnectionError, False), (RuntimeError, True)]
)
def test_rays_native_noise_is_held_back_only_for_a_refused_connection(capfd, raised, shown):
    """Output written straight to file descriptor 2 while connecting (as Ray's C++ core does)
    is dropped when the cluster refuses the connection, and passed on otherwise."""
    from pyramid_sim.jobs import ray_session

    try:
        with ray_session.native_stderr_held(True):
            os.write(2, b"native retry warning\n")
            if raised is not None:
                raise raised("refused" if raised is ConnectionError else "other")
    except Exception as err:
        assert type(err) is raised
    assert ("native retry warning" in capfd.readouterr().err) == shown


def _swept(out: Path, config: SweepConfig, **results) -> list[dict]:
    """The grid's runs appended to `out/sweep.csv` as finished builds; their rows as text."""
    store = SweepStore(out / "sweep.csv")
    for spec in config.runs():
        store.append(
            make_row(
                spec,
                1.0,
                None,
                **{"success": True, "worst_error_xy_mm": 1.5, "max_slip_mm": 0.8, **results},
            )
        )
    return grid_rows(store.rows, config)


def _described(path: Path) -> str:
    from PIL import Image

    with Image.open(path) as image:
        return image.text["Description"]


def test_a_sweep_over_one_parameter_draws_lines_against_it_and_two_draw_heatmaps(tmp_path):
    from pyramid_sim.sweep.run import report

    one = SweepConfig(axes=(parse_axis("friction", "0.5,1,1.5"),), repeats=2)
    table, path = report(_swept(tmp_path / "a", one), one, tmp_path / "a")
    assert path == tmp_path / "a" / "sweep.png"
    assert _described(path) == "pyramid-sim sweep: lines against brick friction"
    assert table.count("2/2") == 3
    two = SweepConfig(axes=(parse_axis("friction", "0.5,1"), parse_axis("brick_mass", "0.5,1")))
    _, path = report(_swept(tmp_path / "b", two), two, tmp_path / "b")
    assert _described(path) == "pyramid-sim sweep: heatmaps over brick friction and brick mass (kg)"


def test_another_group_in_the_same_folder_gets_its_own_plot(tmp_path):
    """Another structure, schedule or robot (or other swept parameters) into one folder:
    sweep.png stays the first sweep's, each other group's plot is named after it, and a
    re-run of a group redraws its own plot."""
    from pyramid_sim.core.structures import StructureSpec
    from pyramid_sim.sweep.run import report

    grid = (parse_axis("friction", "0.5,1"),)
    first = SweepConfig(axes=grid)
    _, path = report(_swept(tmp_path, first), first, tmp_path)
    assert path.name == "sweep.png"
    kept = path.read_bytes()
    others = [
        SweepConfig(axes=grid, structure=StructureSpec("pyramid", layers=2)),
        SweepConfig(axes=grid, schedule="overlap"),
        SweepConfig(axes=grid, robot="baxter"),
        SweepConfig(axes=(parse_axis("grip_force", "10,20"),)),
    ]
    names = []
    for config in others:
        _, path = report(_swept(tmp_path, config), config, tmp_path)
        names.append(path.name)
    assert names == [
        "sweep_panda_lockstep_pyramid_layers=2_both_friction_jitter=2.png",
        "sweep_panda_overlap_pyramid-even_layers=4_both_friction_jitter=2.png",
        "sweep_baxter_lockstep_pyramid-even_layers=4_both_friction_jitter=2.png",
        "sweep_panda_lockstep_pyramid-even_layers=4_both_grip-force_jitter=2.png",
    ]
    assert (tmp_path / "sweep.png").read_bytes() == kept
    assert len(list(tmp_path.glob("*.png"))) == 5
    _, path = report(_swept(tmp_path, first), first, tmp_path)  # the first group again
    assert path == tmp_path / "sweep.png"


def test_a_groups_plot_draws_every_run_of_it_in_the_folder_and_no_other():
    from pyramid_sim.core.structures import StructureSpec
    from pyramid_sim.sweep.report import group_rows

    coarse = SweepConfig(axes=(parse_axis("friction", "0.5,1"),))
    fine = SweepConfig(axes=(parse_axis("friction", "0.7,0.8"),))
    held = SweepConfig(axes=(parse_axis("friction", "0.5,1"), parse_axis("brick_mass", "0.8")))
    other = SweepConfig(axes=(parse_axis("friction", "0.5,1"),), structure=StructureSpec("wall"))
    rows = [
        SweepRow.of(make_row(spec, 1.0, None))
        for config in (coarse, fine, held, other)
        for spec in config.runs()
    ]
    assert sorted(r["friction"] for r in group_rows(rows, fine)) == ["0.5", "0.7", "0.8", "1.0"]
    assert [r["brick_mass"] for r in group_rows(rows, held)] == ["0.8", "0.8"]


def test_a_value_no_run_measured_is_n_a_never_a_dash(tmp_path):
    config = SweepConfig(axes=(parse_axis("friction", "0.5,1"),))
    rows = [
        SweepRow.of(make_row(spec, 1.0, "dropped at the spot", success=False))
        for spec in config.runs()
    ]
    table = summary_table(rows, config)
    cells = [c for line in table.splitlines()[1:] for c in line.split("  ") if c.strip()]
    assert "n/a" in table and "-" not in [c.strip() for c in cells] and " - " not in table


def test_a_sweep_png_not_drawn_by_a_sweep_is_left_alone(tmp_path):
    """A file of that name without a group in it (drawn by hand, or by another program) is
    never drawn over: the sweep's plot is named after its group."""
    from pyramid_sim.sweep.run import report

    (tmp_path / "sweep.png").write_bytes(b"not a plot of ours")
    config = SweepConfig(axes=(parse_axis("friction", "0.5,1"),))
    _, path = report(_swept(tmp_path, config), config, tmp_path)
    assert path.name == "sweep_panda_lockstep_pyramid-even_layers=4_both_friction_jitter=2.png"
    assert (tmp_path / "sweep.png").read_bytes() == b"not a plot of ours"


def test_a_sweep_row_reads_its_cells_typed(tmp_path):
    config = SweepConfig(axes=(parse_axis("friction", "0.5,1"),))
    ok, crashed = (
        make_row(spec, 1.0, reason, success=reason is None, max_slip_mm=0.8)
        for spec, reason in zip(config.runs(), (None, "crashed: ValueError: x"))
    )
    store = SweepStore(tmp_path / "sweep.csv")
    store.append(ok)
    store.append(crashed)
    rows = SweepStore(tmp_path / "sweep.csv").rows  # read back from the file
    assert [r.success for r in rows] == [True, False]
    assert [r.broken for r in rows] == [False, True] and rows[0].failure_reason == ""
    assert rows[0].number("max_slip_mm") == 0.8 and math.isnan(rows[0].number("worst_error_xy_mm"))
    assert rows[1].key == tuple(rows[1][c] for c in COLUMNS[: len(rows[1].key)])


def test_ray_not_installed_is_refused_before_anything_runs(monkeypatch):
    """The one check of the backends: an unknown backend, an address without Ray, and Ray
    asked for but not installed (the sweep's and the recorder's configs call it alike)."""
    import importlib.util

    from pyramid_sim.errors import MachineError
    from pyramid_sim.jobs.backends import check_backend

    real = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util, "find_spec", lambda name, *a: None if name == "ray" else real(name, *a)
    )
    with pytest.raises(MachineError, match="ray is not installed; accepted process"):
        SweepConfig(backend="ray")
    with pytest.raises(ConfigError, match="backend: unknown 'slurm'; accepted process, ray"):
        check_backend("slurm", None)
    check_backend("process", None)  # needs no Ray


@pytest.mark.parametrize("text", ["0_5", "0.5,1_0", "0.5:1:1_0"])
def test_a_sweep_value_with_digit_separators_is_refused_not_read_as_another(text):
    """Python's float() reads 0_5 as 5: a sweep over brick mass would have weighed 5 kg."""
    with pytest.raises(ConfigError, match=f"brick mass.*cannot read {re.escape(repr(text))}"):
        parse_axis("brick_mass", text)
