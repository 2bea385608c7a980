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
    doc = json.loads(json.dumps(result.to_json(), allow_nan=False))
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
        "except pyramid_sim.ConfigError as err:\n"
        "    print(err)\n"
    )
    for backend in ("glfw", "osmesa"):  # no display for GLFW; no libOSMesa on these machines
        env = {"MUJOCO_GL": backend, "PATH": "/usr/bin:/bin"}
        proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                              env=env, cwd=tmp_path, timeout=120)
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
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=env, cwd=tmp_path, timeout=300)
    assert proc.returncode == 0 and proc.stdout.strip() == "True", proc.stderr
    assert (tmp_path / "s.png").stat().st_size > 1000
