"""Headless MP4 through EGL/OSMesa: frame count, size, content; video does not change physics."""

import json
import os
import subprocess
import sys

import numpy as np
import pytest

pytestmark = pytest.mark.physics


def _run(args, tmp_path):
    env = {k: v for k, v in os.environ.items() if k != "MUJOCO_GL"}
    return subprocess.run(
        [
            sys.executable,
            "-m",
            "pyramid_sim.cli",
            "build",
            "--structure",
            "pyramid",
            "--layers",
            "1",
            "--quiet",
            *args,
        ],
        capture_output=True,
        text=True,
        env=env,
        cwd=tmp_path,
        timeout=600,
    )


def test_video_frames_match_sim_time_and_show_the_build(tmp_path):
    import imageio.v2 as imageio

    proc = _run(
        [
            "--out",
            "a",
            "--video",
            "a/build.mp4",
            "--fps",
            "20",
            "--video-width",
            "320",
            "--video-height",
            "240",
            "--snapshot",
            "a/final.png",
        ],
        tmp_path,
    )
    assert proc.returncode == 0, proc.stderr
    assert "a/result.json, a/build.mp4, a/final.png" in proc.stdout  # the summary names each
    doc = json.loads((tmp_path / "a" / "result.json").read_text())
    reader = imageio.get_reader(tmp_path / "a" / "build.mp4")
    frames = [f for f in reader]
    assert abs(len(frames) - doc["sim_time_s"] * 20) <= 1
    assert frames[0].shape == (240, 320, 3)
    picks = [frames[0], frames[len(frames) // 2], frames[-1]]
    assert all(f.std() > 10 for f in picks)  # not blank
    assert np.abs(picks[0].astype(int) - picks[1].astype(int)).mean() > 1  # the scene moves
    assert (tmp_path / "a" / "final.png").stat().st_size > 1000
    assert not [p for p in (tmp_path / "a").iterdir() if p.name.startswith(".")]  # no temp left

    plain = _run(["--out", "b"], tmp_path)
    assert plain.returncode == 0, plain.stderr
    without = json.loads((tmp_path / "b" / "result.json").read_text())
    assert [b["final"] for b in without["bricks"]] == [b["final"] for b in doc["bricks"]]


@pytest.mark.parametrize(
    "args, words",
    [
        (["--video", "/proc/nope/x.mp4"], "mp4 path: '/proc' is not writable"),
        (["--video", "v.mp4", "--camera", "sky"], "camera"),
        (["--video", "v.mp4", "--video-width", "4000"], "video width"),
        (["--video", "v.txt"], "mp4"),
        (["--video", "v.mp4", "--antialias", "3"], "antialias"),
        (["--video", "v.mp4", "--speedup", "0"], "speedup"),
    ],
)
def test_bad_video_options_fail_before_physics(tmp_path, args, words):
    proc = _run(["--out", "c", *args], tmp_path)
    assert proc.returncode == 2
    assert words in proc.stderr and len(proc.stderr.strip().splitlines()) == 1
    assert not (tmp_path / "c").exists()


def test_a_terminated_run_leaves_no_video_behind(tmp_path):
    """SIGTERM mid-build: neither the asked-for MP4 nor its temporary file is left."""
    import signal
    import time

    env = {k: v for k, v in os.environ.items() if k != "MUJOCO_GL"}
    proc = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "pyramid_sim.cli",
            "build",
            "--structure",
            "pyramid",
            "--layers",
            "2",
            "--quiet",
            "--out",
            "t",
            "--video",
            "t/build.mp4",
        ],
        env=env,
        cwd=tmp_path,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and not list((tmp_path / "t").glob(".build.*")):
        time.sleep(0.2)
    assert list((tmp_path / "t").glob(".build.*")), "the recording never started"
    time.sleep(1.0)
    proc.send_signal(signal.SIGTERM)
    assert proc.wait(timeout=60) == 128 + signal.SIGTERM
    assert not (tmp_path / "t").exists()  # nor the folder the run made for it


@pytest.mark.parametrize("name, raised", [("SIGINT", KeyboardInterrupt), ("SIGTERM", SystemExit)])
def test_ctrl_c_or_sigterm_waits_until_the_frame_is_written(name, raised):
    """A Ctrl-C or SIGTERM during a frame's write is held until the write ends, then handled as
    before: ffmpeg never sees a cut frame (it would print its own errors before the run's one
    line)."""
    import signal
    import time

    from pyramid_sim.output.video import signals_held

    def exit_on_sigterm(signum, frame):  # as the command line handles it
        raise SystemExit(128 + signum)

    sig = getattr(signal, name)
    # Python's own Ctrl-C and the command line's SIGTERM, whatever this process was started
    # with (a shell's background job ignores SIGINT).
    handler = signal.default_int_handler if sig == signal.SIGINT else exit_on_sigterm
    before = signal.signal(sig, handler)
    written = []
    try:
        with pytest.raises(raised):
            with signals_held():
                os.kill(os.getpid(), sig)
                time.sleep(0.05)  # an unheld signal would have been handled by now
                written.append("frame")
        assert signal.getsignal(sig) is handler  # let go again
    finally:
        signal.signal(sig, before)
    assert written == ["frame"]


def test_ctrl_c_ends_a_build_in_one_line_leaving_nothing_behind(tmp_path):
    """SIGINT mid-build with video: exit 130, one line and no traceback, no MP4, no temporary
    file and no folder the run made."""
    import signal
    import time

    env = {k: v for k, v in os.environ.items() if k != "MUJOCO_GL"}
    proc = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "pyramid_sim.cli",
            "build",
            "--structure",
            "pyramid",
            "--layers",
            "2",
            "--quiet",
            "--out",
            "i/run",
            "--video",
            "i/run/build.mp4",
        ],
        env=env,
        cwd=tmp_path,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        # Ctrl-C as a terminal gives it, even under a runner that ignores SIGINT (inherited)
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and not list((tmp_path / "i" / "run").glob(".build.*")):
        time.sleep(0.2)
    time.sleep(1.0)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    assert err.strip() == "pyramid-sim: interrupted"
    assert not (tmp_path / "i").exists()


def test_speedup_films_k_simulated_seconds_a_second(tmp_path):
    """--speedup 4 at 20 fps: a frame every 0.2 simulated seconds, a quarter of the frames."""
    import imageio.v2 as imageio

    proc = _run(
        [
            "--out",
            "s",
            "--video",
            "s/fast.mp4",
            "--fps",
            "20",
            "--speedup",
            "4",
            "--video-width",
            "160",
            "--video-height",
            "120",
        ],
        tmp_path,
    )
    assert proc.returncode == 0, proc.stderr
    doc = json.loads((tmp_path / "s" / "result.json").read_text())
    frames = sum(1 for _ in imageio.get_reader(tmp_path / "s" / "fast.mp4"))
    assert abs(frames - doc["sim_time_s"] * 20 / 4) <= 1
    assert doc["video"]["speedup"] == 4.0 and doc["video"]["frames"] == frames
