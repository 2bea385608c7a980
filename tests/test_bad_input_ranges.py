"""Each accepted range is held in one place (a Bound in config.py, as the parameter table holds
the physics knobs'), and both the help text and the refusal read it: the two cannot disagree,
as the video flags' help ("1 to 120") and their errors ("[1, 120]") once did."""

import argparse

import pytest

from pyramid_sim.cli import make_parser
from pyramid_sim.config import (
    SPAWN_JITTER_MM,
    SPEEDUP,
    VIDEO_FPS,
    VIDEO_HEIGHT,
    VIDEO_WIDTH,
    antialias_text,
)
from pyramid_sim.params import NOISE

VIDEO = ["--video", "b.mp4"]


def _help(command: str, flag: str) -> str:
    """The help text of `flag` of `command`, on one line."""
    (sub,) = [a for a in make_parser()._actions if isinstance(a, argparse._SubParsersAction)]
    (action,) = [a for a in sub.choices[command]._actions if flag in a.option_strings]
    return " ".join(action.help.split())


@pytest.mark.parametrize(
    "command, flag, accepted, refused_args",
    [
        ("build", "--fps", VIDEO_FPS.text, [*VIDEO, "--fps", "121"]),
        ("build", "--video-width", VIDEO_WIDTH.text, [*VIDEO, "--video-width", "2000"]),
        ("build", "--video-height", VIDEO_HEIGHT.text, [*VIDEO, "--video-height", "2000"]),
        ("build", "--speedup", SPEEDUP.text, [*VIDEO, "--speedup", "200"]),
        ("build", "--antialias", antialias_text(), [*VIDEO, "--antialias", "3"]),
        ("build", "--spawn-jitter", SPAWN_JITTER_MM.text, ["--spawn-jitter", "20"]),
        ("sweep", "--spawn-jitter", SPAWN_JITTER_MM.text, ["--spawn-jitter", "20"]),
        ("record", "--spawn-jitter", SPAWN_JITTER_MM.text, ["--spawn-jitter", "20"]),
        ("record", "--noise", NOISE.text, ["--noise", "0.2"]),
    ],
)
def test_the_help_and_the_refusal_state_the_same_range_from_one_place(
    tmp_path, monkeypatch, refused, command, flag, accepted, refused_args
):
    monkeypatch.chdir(tmp_path)
    assert accepted in _help(command, flag)
    err = refused([command, "--layers", "1", *refused_args, "--out", "run"])
    assert f"accepted {accepted}" in err
    assert list(tmp_path.iterdir()) == []


def test_a_video_size_that_is_odd_names_both_ranges_as_the_help_does(refused, tmp_path):
    err = refused(["build", *VIDEO, "--video-width", "17", "--out", str(tmp_path / "run")])
    assert f"accepted width {VIDEO_WIDTH.text}, height {VIDEO_HEIGHT.text}" in err


def test_a_bound_checks_what_its_text_states():
    from pyramid_sim.errors import ConfigError

    for value in (VIDEO_FPS.low, VIDEO_FPS.high):
        VIDEO_FPS.check(value)
    for value in (VIDEO_FPS.low - 1, VIDEO_FPS.high + 1, float("nan")):
        with pytest.raises(ConfigError, match=r"fps: .* accepted \[1, 120\]"):
            VIDEO_FPS.check(value)


def test_an_unknown_action_mode_is_refused_naming_every_mode():
    from pyramid_sim.choices import in_words
    from pyramid_sim.errors import ConfigError
    from pyramid_sim.learning.task.contract import check_modes

    with pytest.raises(ConfigError) as refused:
        check_modes("torque", None)
    assert str(refused.value) == (
        "action mode: unknown 'torque'; accepted joint, relative, ee, waypoint, anchored, delta or absolute"
    )
    assert in_words(["a"]) == "a" and in_words([1, 2]) == "1 or 2"
