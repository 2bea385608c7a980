"""The Python API builds: a typed result that records its inputs, and rendering that refuses
before any physics when no OpenGL can be had."""

import json
import subprocess
import sys

import pyramid_sim


def test_build_returns_a_typed_result_that_records_its_inputs():
    result = pyramid_sim.build("pyramid", layers=1, friction=0.8, brick_mass=0.6, seed=3)
    assert isinstance(result, pyramid_sim.BuildResult)
    assert result.success, result.failure_reason
    (brick,) = result.bricks
    assert brick.placed and brick.error_xy_mm < 5.0 and brick.final is not None
    doc = json.loads(result.to_json())  # the text of result.json: strict JSON
    assert doc == result.to_dict()
    assert doc["bricks"][0]["final"]["position"] == list(brick.final.position)
    settings = doc["inputs"]["settings"]
    assert settings["brick"]["friction"] == 0.8 and settings["brick"]["mass"] == 0.6
    assert doc["inputs"]["seed"] == 3 and doc["inputs"]["structure"] == "pyramid"
    assert set(doc["versions"]) >= {"pyramid_sim", "mujoco", "mink", "numpy", "python"}
    assert doc["versions"]["pyramid_sim"] == pyramid_sim.__version__


def test_rendering_without_opengl_is_refused_before_any_physics(tmp_path):
    code = (
        "import pyramid_sim\n"
        "try:\n"
        "    import mujoco\n"  # where it loads, any physics step would fail the run loudly
        "    mujoco.mj_step = None\n"
        "except Exception:\n"
        "    pass\n"
        "try:\n"
        f"    pyramid_sim.build('pyramid', layers=1, video={str(tmp_path / 'b.mp4')!r})\n"
        "except pyramid_sim.MachineError as err:\n"
        "    print(err)\n"
    )
    for backend in ("glfw", "osmesa"):  # no display for GLFW; no libOSMesa on these machines
        env = {"MUJOCO_GL": backend, "PATH": "/usr/bin:/bin"}
        proc = subprocess.run(
            [sys.executable, "-c", code],
            capture_output=True,
            text=True,
            env=env,
            cwd=tmp_path,
            timeout=120,
        )
        assert proc.returncode == 0 and proc.stdout.startswith("video:"), proc.stderr
    assert not list(tmp_path.glob("*.mp4"))


def test_a_build_that_does_not_render_leaves_a_later_one_able_to(tmp_path):
    # MuJoCo binds its GL backend on first import: the first build, without video, must already
    # have chosen a headless one, or the second cannot render.
    code = (
        "import pyramid_sim\n"
        "assert pyramid_sim.build('pyramid', layers=1).success\n"
        f"result = pyramid_sim.build('pyramid', layers=1, snapshot={str(tmp_path / 's.png')!r})\n"
        "print(result.success)\n"
    )
    env = {"PATH": "/usr/bin:/bin", "HOME": str(tmp_path)}  # no MUJOCO_GL
    proc = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        env=env,
        cwd=tmp_path,
        timeout=300,
    )
    assert proc.returncode == 0 and proc.stdout.strip() == "True", proc.stderr
    assert (tmp_path / "s.png").stat().st_size > 1000


def test_a_result_saves_exactly_the_text_the_command_line_writes(tmp_path):
    from pyramid_sim.cli import main

    assert (
        main(
            [
                "build",
                "--structure",
                "pyramid",
                "--layers",
                "1",
                "--quiet",
                "--out",
                str(tmp_path / "cli"),
            ]
        )
        == 0
    )
    written = (tmp_path / "cli" / "result.json").read_text()
    result = pyramid_sim.build("pyramid", layers=1)
    result.save(tmp_path / "api.json")
    saved = (tmp_path / "api.json").read_text()
    assert saved == result.to_json()
    # The same build from both: the same document, the wall-clock fields aside.
    clock = ("wall_time_s", "real_time_factor")
    cli_doc, api_doc = json.loads(written), json.loads(saved)
    assert {k: v for k, v in cli_doc.items() if k not in clock} == {
        k: v for k, v in api_doc.items() if k not in clock
    }
    assert list(cli_doc) == list(api_doc)  # the same fields in the same order


def test_mujoco_imported_first_still_renders_headless(tmp_path):
    """A notebook imports mujoco before pyramid_sim, without MUJOCO_GL: MuJoCo then binds GLFW,
    which needs a display. The build makes its EGL context directly and renders."""
    code = (
        "import mujoco\n"
        "import pyramid_sim\n"
        "vc = pyramid_sim.VideoConfig(width=160, height=120, speedup=20)\n"
        f"r = pyramid_sim.build('pyramid', layers=1, video={str(tmp_path / 'b.mp4')!r}, "
        f"snapshot={str(tmp_path / 's.png')!r}, video_config=vc)\n"
        "print(r.success, r.video.frames)\n"
    )
    env = {"PATH": "/usr/bin:/bin", "HOME": str(tmp_path)}  # no MUJOCO_GL, no DISPLAY
    proc = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        env=env,
        cwd=tmp_path,
        timeout=300,
    )
    assert proc.returncode == 0, proc.stderr
    success, frames = proc.stdout.split()
    assert success == "True" and int(frames) > 10, proc.stdout
    assert (tmp_path / "b.mp4").stat().st_size > 1000
    assert (tmp_path / "s.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
