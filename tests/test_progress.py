"""Progress on stderr: bars on a terminal whose totals are never passed, a few plain lines
elsewhere, and a resumed sweep's rate counting only the runs it ran."""

import io
import re

from pyramid_sim.cli import main
from pyramid_sim.cli.progress import Progress, duration


class Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_off_a_terminal_a_whole_build_is_a_few_plain_lines():
    log = io.StringIO()
    with Progress("bricks", 20, "brick", count_unit="frame", stream=log) as progress:
        progress.start()
        for brick in range(1, 21):
            progress.count(97)
            progress.advance_to(brick)
        progress.count(30)  # the settling after the last brick
    lines = log.getvalue().splitlines()
    assert len(lines) == 10 and "\r" not in log.getvalue()
    assert lines[0].startswith("bricks: 2/20 bricks (10%) in ")
    assert lines[-1].startswith("bricks: 20/20 bricks (100%) in ") and "1940 frames" in lines[-1]


def test_a_recordings_hooks_count_episodes_and_each_frame_once():
    """record's hooks: a resumed run starts at the episodes it found; an episode's frames as
    they grow (one worker) or all at once (many) are counted once each."""
    log = io.StringIO()
    with Progress("episodes", 5, "episode", count_unit="frame", stream=log) as progress:
        on_frame, on_episode = progress.recording_hooks()
        on_episode(2)  # two found done: not this run's
        on_frame(2, 10)
        on_frame(2, 30)  # the same episode, grown
        on_episode(3)
        on_frame(3, 25)  # from a worker: whole
        on_frame(4, 25)
        on_episode(5)
        assert (progress.initial, progress.n, progress.counted) == (2, 5, 80)
    assert "80 frames" in log.getvalue().splitlines()[-1]


def test_off_a_terminal_a_build_stopped_short_says_where():
    log = io.StringIO()
    with Progress("bricks", 20, "brick", stream=log) as progress:
        progress.start()
        progress.advance_to(3)
    assert log.getvalue().splitlines()[-1].startswith("bricks: 3/20 bricks (15%)")


def test_a_resumed_sweep_rates_only_the_runs_it_ran():
    now = [100.0]
    log = io.StringIO()
    with Progress("sweep", 10, "build", stream=log, clock=lambda: now[0]) as progress:
        progress.start(done=8)  # already in sweep.csv
        now[0] += 40.0
        progress.advance()
        now[0] += 40.0
        progress.advance()
    lines = log.getvalue().splitlines()
    assert lines[0] == "sweep: 8/10 builds done before"
    assert lines[-1] == "sweep: 10/10 builds (100%) in 1 min 20 s, 40.0 s/build"


def test_off_a_terminal_each_line_says_the_time_left_at_this_runs_pace():
    now = [0.0]
    log = io.StringIO()
    with Progress("episodes", 4, "episode", stream=log, clock=lambda: now[0]) as progress:
        progress.start()
        for _ in range(4):
            now[0] += 30.0
            progress.advance()
    assert log.getvalue().splitlines() == [
        "episodes: 1/4 episodes (25%) in 30 s, 30.0 s/episode, about 1 min 30 s left",
        "episodes: 2/4 episodes (50%) in 1 min 0 s, 30.0 s/episode, about 1 min 0 s left",
        "episodes: 3/4 episodes (75%) in 1 min 30 s, 30.0 s/episode, about 30 s left",
        "episodes: 4/4 episodes (100%) in 2 min 0 s, 30.0 s/episode",
    ]


def test_on_a_terminal_the_bar_says_the_units_done_and_the_time_left():
    now = [0.0]
    screen = Terminal()
    with Progress("episodes", 4, "episode", stream=screen, clock=lambda: now[0]) as progress:
        progress.start()
        progress.advance()
        progress.advance()
    bar = screen.getvalue().split("\r")[-1]
    assert "2/4" in bar and re.search(r"\[\d\d:\d\d<\d\d:\d\d", bar), bar  # [elapsed<left
    assert "\n" not in screen.getvalue().rstrip("\n")  # redrawn in place, not a line a step


def test_on_a_terminal_a_resumed_sweep_starts_at_its_done_runs():
    screen = Terminal()
    with Progress("sweep", 10, "build", stream=screen) as progress:
        progress.start(done=8)
        assert progress.tty and "8/10" in screen.getvalue()
        progress.advance()
    assert "9/10" in screen.getvalue()


def _frame_counts(text: str) -> list[tuple[int, int]]:
    return [(int(n), int(total)) for n, total in re.findall(r"frames:[^\r\n]*?(\d+)/(\d+)", text)]


def test_on_a_terminal_the_frames_count_never_passes_its_total_and_ends_on_it(
    tmp_path, monkeypatch, fake_build
):
    """The film goes on after the last brick (the scene settles): a total guessed from the
    pace would be passed. The count has no total until the end, then the exact one."""
    screen = Terminal()
    monkeypatch.setattr("sys.stderr", screen)
    fake_build.frames = 40
    out = tmp_path / "run"
    assert main(["build", "--layers", "1", "--out", str(out), "--video", str(out / "b.mp4")]) == 0
    counts = _frame_counts(screen.getvalue())
    assert counts and all(n <= total for n, total in counts)
    assert counts[-1] == (120, 120)  # two bricks and the settling


def test_a_build_logged_off_a_terminal_writes_plain_lines(tmp_path, capsys, fake_build):
    fake_build.frames = 40
    out = tmp_path / "run"
    assert (
        main(
            [
                "build",
                "--structure",
                "pyramid-even",
                "--layers",
                "2",
                "--out",
                str(out),
                "--video",
                str(out / "b.mp4"),
            ]
        )
        == 0
    )
    err = capsys.readouterr().err
    assert "\r" not in err and 1 <= len(err.splitlines()) <= 12
    assert err.splitlines()[-1].startswith("bricks: 6/6 bricks (100%)")


def test_quiet_says_nothing(tmp_path, capsys, fake_build):
    assert main(["build", "--layers", "1", "--quiet", "--out", str(tmp_path / "run")]) == 0
    assert capsys.readouterr().err == ""


def test_durations_read_as_a_person_would_say_them():
    assert [duration(s) for s in (42.4, 257, 3725)] == ["42 s", "4 min 17 s", "1 h 02 min"]
