"""One run at a time in an output folder: a second build or sweep is refused while the first
holds it, a killed holder blocks nobody, and no run leaves a lock file or a folder it made."""

import os
import signal
import subprocess
import sys
import textwrap

import pytest

from pyramid_sim.cli import main
from pyramid_sim.output.lock import LOCK_NAME, FolderBusy, folder_lock, holding


def _build(out, *extra):
    return [
        "build",
        "--structure",
        "pyramid",
        "--layers",
        "1",
        "--quiet",
        "--out",
        str(out),
        *extra,
    ]


def test_a_second_build_into_the_folder_of_a_running_one_is_refused(tmp_path, capsys, fake_build):
    out = tmp_path / "run"
    second = []

    def start_another(i):
        second.append(main(_build(out)))
        second.append(capsys.readouterr().err)

    fake_build.during = start_another
    assert main(_build(out)) == 0
    code, err = second
    assert code == 2 and len(err.strip().splitlines()) == 1
    assert f"out: {str(out)!r} is held by another pyramid-sim run (pid {os.getpid()})" in err
    assert (out / "result.json").exists() and not (out / LOCK_NAME).exists()


def test_a_sweep_into_a_held_folder_is_refused_before_it_runs(tmp_path, refused, fake_build):
    out = tmp_path / "sweep"
    with folder_lock(out):
        err = refused(
            [
                "sweep",
                "--structure",
                "pyramid",
                "--layers",
                "1",
                "--friction",
                "1",
                "--quiet",
                "--out",
                str(out),
            ]
        )
        assert "is held by another pyramid-sim run" in err
        assert [p.name for p in out.iterdir()] == [LOCK_NAME]  # no sweep.csv begun
    assert list(out.iterdir()) == []


def test_a_video_folder_outside_out_is_held_too_and_a_refusal_leaves_nothing(
    tmp_path, refused, fake_build
):
    films, out = tmp_path / "films", tmp_path / "a" / "run"
    with folder_lock(films):
        err = refused(_build(out, "--video", str(films / "a.mp4")))
        assert f"mp4 path: {str(films)!r} is held by another pyramid-sim run" in err
    assert not (tmp_path / "a").exists()  # made for its lock, removed with it


def test_a_lock_left_by_a_killed_run_does_not_block(tmp_path, capsys, fake_build):
    out = tmp_path / "run"
    holder = subprocess.Popen(
        [
            sys.executable,
            "-c",
            textwrap.dedent(f"""
            import sys, time
            from pathlib import Path
            from pyramid_sim.output.lock import folder_lock
            with folder_lock(Path({str(out)!r})):
                print("held", flush=True)
                time.sleep(60)
        """),
        ],
        stdout=subprocess.PIPE,
        text=True,
        env={**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)},
    )
    try:
        assert holder.stdout.readline().strip() == "held"
        assert (out / LOCK_NAME).read_text().strip() == str(holder.pid)
        with pytest.raises(FolderBusy, match=f"pid {holder.pid}"):
            with folder_lock(out):
                pass
    finally:
        holder.send_signal(signal.SIGKILL)
        holder.wait()
    assert (out / LOCK_NAME).exists()  # stale: its holder died without a word
    assert main(_build(out)) == 0
    assert (out / "result.json").exists() and not (out / LOCK_NAME).exists()


def test_an_interrupted_run_leaves_no_lock_and_no_folder_it_made(tmp_path, capsys, fake_build):
    def interrupt(i):
        raise KeyboardInterrupt

    fake_build.during = interrupt
    assert main(_build(tmp_path / "new" / "run")) == 130
    assert list(tmp_path.iterdir()) == []


def test_a_lock_file_removed_before_it_was_locked_is_taken_afresh(tmp_path, monkeypatch):
    """The holder removes the file between another run's open and its lock: that run must not
    hold the removed file (nobody else would see it), but the one now at the path."""
    import fcntl

    from pyramid_sim.output import lock

    real_flock, calls = fcntl.flock, []

    def flock_after_the_holder_left(fd, operation):
        calls.append(fd)
        if len(calls) == 1:
            os.unlink(tmp_path / LOCK_NAME)  # as the holder does when it ends
        return real_flock(fd, operation)

    monkeypatch.setattr(lock.fcntl, "flock", flock_after_the_holder_left)
    with folder_lock(tmp_path) as path:
        assert len(calls) == 2  # tried afresh
        monkeypatch.setattr(lock.fcntl, "flock", real_flock)
        with pytest.raises(FolderBusy):  # the file at the path is the one held
            with folder_lock(tmp_path):
                pass
        assert path.read_text().strip() == str(os.getpid())
    assert not path.exists()


def test_folders_are_taken_once_each_in_one_order(tmp_path):
    asked = [(tmp_path / "b", "out"), (tmp_path / "a", "mp4 path"), (tmp_path / "b", "png path")]
    with holding(asked):
        assert sorted(p.parent.name for p in tmp_path.glob(f"*/{LOCK_NAME}")) == ["a", "b"]
    assert not list(tmp_path.glob(f"*/{LOCK_NAME}"))


def test_ctrl_c_while_a_frame_renders_is_an_interruption(tmp_path, capsys, fake_build):
    """A Ctrl-C inside the OpenGL binding's argument conversion reaches Python as ctypes'
    ArgumentError ("argument 1: KeyboardInterrupt"): exit 130 and one line, as any Ctrl-C."""
    import ctypes

    def interrupt(i):
        raise ctypes.ArgumentError("argument 1: KeyboardInterrupt: ")

    fake_build.during = interrupt
    assert main(_build(tmp_path / "new" / "run")) == 130
    assert capsys.readouterr().err.strip() == "pyramid-sim: interrupted"
    assert list(tmp_path.iterdir()) == []
    fake_build.during = lambda i: (_ for _ in ()).throw(ctypes.ArgumentError("argument 1: x"))
    with pytest.raises(ctypes.ArgumentError):  # a real one is a bug: its traceback shows
        main(_build(tmp_path / "run"))


@pytest.mark.physics
@pytest.mark.parametrize("command", ["scene", "record", "evaluate"])
def test_every_command_that_writes_is_refused_a_folder_another_run_holds(
    tmp_path, refused, command
):
    """One rule for every command that writes: `scene` wrote into a folder a running build
    held, and `record` and `evaluate` held their --out only from the command line (the
    library now holds it, as `build` does)."""
    out = tmp_path / "run"
    argv = {
        "scene": ["scene", "--layers", "1", "--out", str(out / "scene.xml")],
        "record": ["record", "--layers", "1", "--cameras", "none", "--out", str(out)],
        "evaluate": ["evaluate", "--layers", "1", "--episodes", "1", "--out", str(out)],
    }[command]
    with folder_lock(out):
        err = refused([*argv[:1], "--structure", "pyramid-even", *argv[1:]])
    assert f"out: {str(out)!r} is held by another pyramid-sim run (pid {os.getpid()})" in err
    assert list(out.iterdir()) == []  # nothing written beside the holder's (gone) lock
