"""What a new user trips on, smoothed: --version, view without a display, a sweep that
measured nothing, plans that build would refuse, and the scene written for inspection."""

import subprocess
import sys
from pathlib import Path

import pytest

import pyramid_sim
from pyramid_sim.cli import main, make_parser

ROOT = Path(__file__).resolve().parents[1]


def test_version(capsys):
    with pytest.raises(SystemExit) as done:
        main(["--version"])
    assert done.value.code == 0
    assert capsys.readouterr().out.strip() == f"pyramid-sim {pyramid_sim.__version__}"


def test_view_without_a_display_is_one_line_and_leaves_no_log(tmp_path, monkeypatch, refused):
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    assert "no display" in refused(["view", "--layers", "1"])
    assert list(tmp_path.iterdir()) == []  # no MUJOCO_LOG.TXT


def test_a_scene_path_must_be_mjb_or_xml(tmp_path, refused):
    assert ".mjb or .xml" in refused(["scene", "--out", str(tmp_path / "scene.txt")])
    assert list(tmp_path.iterdir()) == []


@pytest.mark.physics
def test_plan_refuses_what_build_would(capsys, refused):
    assert "largest reachable is layers 5" in refused(["plan", "--layers", "12"])


@pytest.mark.physics
def test_the_size_suggested_for_an_unreachable_wall_is_whole_and_accepted(capsys, refused):
    # A wall is sized by its width at three courses: the bricks asked for change with it.
    err = refused(["plan", "--structure", "wall", "--wall-width", "7", "--bricks", "22"])
    assert "the largest reachable is width 6 (bricks=19 width=6)" in err
    assert main(["plan", "--structure", "wall", "--wall-width", "6", "--bricks", "19"]) == 0
    err = refused(["plan", "--structure", "towers", "--towers", "4", "--layers", "6"])
    assert "no towers value brings towers with layers=6 within reach" in err


@pytest.mark.physics
@pytest.mark.parametrize("suffix", [".mjb", ".xml"])
def test_the_scene_a_build_runs_is_written_for_inspection(tmp_path, capsys, suffix):
    import mujoco

    out = tmp_path / f"scene{suffix}"
    assert main(["scene", "--structure", "pyramid", "--layers", "2", "--friction", "0.4",
                 "--grip-force", "12", "--out", str(out)]) == 0
    model = (mujoco.MjModel.from_binary_path if suffix == ".mjb" else mujoco.MjModel.from_xml_path)(
        str(out))
    assert model.geom("brick05/geom").friction[0] == pytest.approx(0.4)  # 3 bricks + 3 spares
    assert model.geom("table_top").friction[0] == pytest.approx(0.4)
    assert model.actuator("left/gripper").forcerange[1] == pytest.approx(12.0)
    assert str(out) in capsys.readouterr().out


@pytest.mark.physics
def test_a_sweep_whose_every_run_timed_out_fails(tmp_path):
    proc = subprocess.run(
        [sys.executable, "-m", "pyramid_sim.cli", "sweep", "--structure", "pyramid", "--layers",
         "1", "--friction", "1", "--timeout", "0.5", "--workers", "1", "--quiet", "--out",
         str(tmp_path / "s")], capture_output=True, text=True, timeout=300,
    )
    assert proc.returncode == 1, proc.stderr
    assert "sweep incomplete: 1 of 1 runs crashed or timed out" in proc.stderr
    rows = (tmp_path / "s" / "sweep.csv").read_text().splitlines()
    assert len(rows) == 2 and "timeout" in rows[1]


def test_an_unknown_robot_is_one_line_listing_the_presets(refused):
    err = refused(["build", "--robot", "kuka"])
    assert "robot: unknown 'kuka'; accepted panda, baxter" in err


def test_render_script_refuses_an_out_without_a_folder_in_one_line(tmp_path):
    script = ROOT / "scripts" / "render_mp4.py"
    proc = subprocess.run([sys.executable, str(script), "--layers", "1", "--out"],
                          capture_output=True, text=True, cwd=tmp_path, timeout=60)
    assert proc.returncode == 2 and proc.stderr.strip().splitlines() == [
        "render_mp4.py: error: argument --out: expected one argument"
    ]
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    "args, out, video",
    [
        ([], "runs/render", "runs/render/build.mp4"),
        (["--out=runs/a"], "runs/a", "runs/a/build.mp4"),
        (["--out", "runs/b", "--layers", "1"], "runs/b", "runs/b/build.mp4"),
        (["--out", "runs/c", "--video=films/c.mp4"], "runs/c", "films/c.mp4"),
    ],
)
def test_render_script_writes_where_it_is_told_in_any_spelling(args, out, video):
    import importlib.util

    spec = importlib.util.spec_from_file_location("render_mp4", ROOT / "scripts" / "render_mp4.py")
    script = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(script)
    command, _ = script.build_args(args)
    parsed = make_parser().parse_args(command)  # the CLI reads it: the last --out wins
    assert (str(parsed.out), str(parsed.video)) == (out, video)
