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
def test_scene_refuses_what_plan_and_build_would_writing_nothing(tmp_path, refused):
    """One rule for what a size may be, in every command: the SO-101 pair's 12-layer
    pyramid is out of its reach, so no 81-brick model is written."""
    out = tmp_path / "s.xml"
    argv = ["--robot", "so101", "--structure", "pyramid", "--layers", "12"]
    plan_err = refused(["plan", *argv])
    scene_err = refused(["scene", *argv, "--out", str(out)])
    assert "largest reachable is layers 3" in scene_err
    assert scene_err == plan_err and list(tmp_path.iterdir()) == []


@pytest.mark.physics
def test_a_size_whose_zone_reaches_under_a_waiting_arm_is_refused_up_front(refused):
    """The SO-101 pair's 4-layer even pyramid is within reach of every pose, but its shared
    zone covers the left arm's forearm at its clear pose: built, it failed `shared_zone` after
    156 s with every brick placed. Refused before physics, naming why and what builds."""
    err = refused(["plan", "--robot", "so101", "--structure", "pyramid-even", "--layers", "4"])
    assert "the left arm waiting at its clear pose has its left/lower_arm inside the shared " in err
    assert "the largest reachable is layers 3" in err


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
    assert (
        main(
            [
                "scene",
                "--structure",
                "pyramid",
                "--layers",
                "2",
                "--friction",
                "0.4",
                "--grip-force",
                "12",
                "--out",
                str(out),
            ]
        )
        == 0
    )
    model = (mujoco.MjModel.from_binary_path if suffix == ".mjb" else mujoco.MjModel.from_xml_path)(
        str(out)
    )
    assert model.geom("brick05/geom").friction[0] == pytest.approx(0.4)  # 3 bricks + 3 spares
    assert model.geom("table_top").friction[0] == pytest.approx(0.4)
    assert model.actuator("left/gripper").forcerange[1] == pytest.approx(12.0)
    assert str(out) in capsys.readouterr().out


@pytest.mark.physics
def test_a_sweep_whose_every_run_timed_out_fails(tmp_path):
    """The timeout counts from when the worker has imported MuJoCo: a one-brick build takes
    0.4 s of it, so 0.01 s times out whatever the machine's load (0.5 s once passed only
    because the import was counted)."""
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "pyramid_sim.cli",
            "sweep",
            "--structure",
            "pyramid",
            "--layers",
            "1",
            "--friction",
            "1",
            "--timeout",
            "0.01",
            "--workers",
            "1",
            "--quiet",
            "--out",
            str(tmp_path / "s"),
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert proc.returncode == 1, proc.stderr
    assert "sweep incomplete: 1 of 1 runs crashed or timed out" in proc.stderr
    assert "with --retry-failed (and a larger --timeout) runs them again" in proc.stderr
    rows = (tmp_path / "s" / "sweep.csv").read_text().splitlines()
    assert len(rows) == 2 and "timeout" in rows[1]
    # Resumed as it was, the failed point is not run again; with --retry-failed it is, its
    # new row appended, and the later row stands.
    again = subprocess.run(
        [*proc.args, "--timeout", "600"], capture_output=True, text=True, timeout=300
    )
    assert again.returncode == 1 and "sweep incomplete: 1 of 1" in again.stderr
    retried = subprocess.run(
        [*proc.args, "--timeout", "600", "--retry-failed"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert retried.returncode == 0, retried.stderr
    assert "1/1 builds succeeded (1 run now, 0 already in the CSV)" in retried.stdout
    rows = (tmp_path / "s" / "sweep.csv").read_text().splitlines()
    assert len(rows) == 3 and "timeout" in rows[1] and ",true," in rows[2]


@pytest.mark.physics
def test_a_sweep_csv_that_is_not_text_is_refused_and_left_as_it_was(tmp_path, refused):
    """It was a UnicodeDecodeError traceback."""
    out = tmp_path / "s"
    out.mkdir()
    junk = (bytes(range(128, 256)) + b"\n") * 3
    (out / "sweep.csv").write_bytes(junk)
    line = refused(["sweep", "--structure", "pyramid", "--layers", "1", "--out", str(out)])
    assert f"out: {str(out / 'sweep.csv')!r} is not a sweep's table (" in line
    assert "accepted a new folder, or one whose sweep.csv a sweep wrote" in line
    assert (out / "sweep.csv").read_bytes() == junk and sorted(out.iterdir()) == [out / "sweep.csv"]


def test_an_unknown_robot_is_one_line_listing_the_presets(refused):
    err = refused(["build", "--robot", "kuka"])
    assert "robot: unknown 'kuka'; accepted panda, baxter" in err


def test_render_script_refuses_an_out_without_a_folder_in_one_line(tmp_path):
    script = ROOT / "scripts" / "render_mp4.py"
    proc = subprocess.run(
        [sys.executable, str(script), "--layers", "1", "--out"],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        timeout=60,
    )
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


@pytest.mark.parametrize("old, new", [("--width", "--video-width"), ("--height", "--video-height")])
@pytest.mark.parametrize("value", [["480"], []])
def test_the_video_size_flags_old_names_are_refused_naming_the_new(
    tmp_path, refused, fake_build, old, new, value
):
    out = tmp_path / "run"
    err = refused(["build", "--out", str(out), "--video", str(out / "b.mp4"), old, *value])
    assert f"{old} is now {new} (the video's" in err
    assert not out.exists()


@pytest.mark.parametrize(
    "args, words",
    [
        (["--fps", "20"], "--fps: a setting of the video, but no --video is given"),
        (["--speedup", "4"], "--speedup: a setting of the video"),
        (
            ["--video-width", "320"],
            "--video-width: a setting of the video and the snapshot, but "
            "neither --video nor --snapshot is given",
        ),
        (["--video-height", "240"], "--video-height: a setting of the video and the snapshot"),
        (["--camera", "top"], "--camera: a setting of the video and the snapshot"),
        (["--shadows"], "--shadows: a setting"),
        (["--no-shadows"], "--shadows: a setting"),
        (["--antialias", "4"], "--antialias: a setting"),
        (["--snapshot", "s.png", "--fps", "20"], "--fps: a setting of the video, but no --video"),
    ],
)
def test_a_video_setting_without_its_output_is_refused_not_ignored(
    tmp_path, monkeypatch, refused, fake_build, args, words
):
    monkeypatch.chdir(tmp_path)
    err = refused(["build", "--layers", "1", "--out", "run", *args])
    assert words in err and "accepted with --video PATH.mp4" in err
    assert list(tmp_path.iterdir()) == []


def test_a_still_takes_the_settings_it_uses(tmp_path, capsys, fake_build):
    out = tmp_path / "run"
    assert (
        main(
            [
                "build",
                "--layers",
                "1",
                "--quiet",
                "--out",
                str(out),
                "--snapshot",
                str(out / "s.png"),
                "--camera",
                "top",
                "--video-width",
                "320",
            ]
        )
        == 0
    )


def test_no_command_prints_the_usage_and_exits_2(capsys):
    assert main([]) == 2
    captured = capsys.readouterr()
    assert captured.out == "" and captured.err.startswith("usage: pyramid-sim")
    assert all(
        name in captured.err for name in ("plan", "build", "view", "sweep", "reach", "scene")
    )


def _commands() -> dict:
    import argparse

    (sub,) = [a for a in make_parser()._actions if isinstance(a, argparse._SubParsersAction)]
    return sub.choices


def test_help_shows_every_default_and_the_choices():
    import argparse

    from pyramid_sim.choices import ARM_CHOICES, CAMERAS

    no_default = {"--video", "--snapshot", "--goals"}  # nothing is written, or read, unless given
    missing = []
    for name, parser in _commands().items():
        for action in parser._actions:
            flag = action.option_strings[0] if action.option_strings else None
            if (
                flag is None
                or action.help == argparse.SUPPRESS
                or action.required
                or isinstance(action, argparse._HelpAction)
                or flag in no_default
            ):
                continue
            if "default" not in action.help:
                missing.append(f"{name} {flag}")
    assert missing == []
    build = _commands()["build"].format_help()
    assert "(default runs/latest)" in " ".join(build.split())
    assert "(default runs/sweep)" in " ".join(_commands()["sweep"].format_help().split())
    build_help = _help_of(_commands()["build"])
    assert all(arm in build_help["--arms"] for arm in ARM_CHOICES)
    assert all(camera in build_help["--camera"] for camera in CAMERAS)
    assert all(arm in _help_of(_commands()["reach"])["--arms"] for arm in (*ARM_CHOICES, "all"))


def _help_of(parser) -> dict:
    return {a.option_strings[0]: a.help for a in parser._actions if a.option_strings}


@pytest.mark.parametrize("command", ["record", "evaluate"])
def test_the_seed_of_record_and_evaluate_is_the_first_episodes(command, capsys):
    with pytest.raises(SystemExit):
        main([command, "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "--seed SEED the first episode's; episode i is seed + i" in text
    assert "spawn jitter (default" not in text
