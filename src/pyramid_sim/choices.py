"""The names a setting can take, as Literal types for the type checker and as the tuples the
command line and the settings' checks read: one list of each, here."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import Literal, get_args

Arm = Literal["left", "right"]
ArmChoice = Literal["both", "left", "right"]  # who builds: both arms (split) or one alone
Schedule = Literal["lockstep", "overlap"]
RobotName = Literal["panda", "baxter", "so101"]
Camera = Literal["overview", "front", "top"]
Backend = Literal["process", "ray"]  # where a sweep's builds or a recording's episodes run

ARMS: tuple[Arm, ...] = get_args(Arm)  # left first: the order of every per-arm array
ARM_CHOICES: tuple[ArmChoice, ...] = get_args(ArmChoice)
SCHEDULES: tuple[Schedule, ...] = get_args(Schedule)
ROBOT_NAMES: tuple[RobotName, ...] = get_args(RobotName)
CAMERAS: tuple[Camera, ...] = get_args(Camera)
BACKENDS: tuple[Backend, ...] = get_args(Backend)
# How much one learning episode differs from the next (learning/task/variation.py).
VARIATIONS = ("fixed", "layout", "full")
DEFAULT_VARIATION = "layout"


@dataclass(frozen=True)
class ModeWords:
    """What is known of an action mode without MuJoCo (learning/action_modes/registry.py has
    a class for each name, and a test holds the two equal): the mode in a few words for the
    command line's help, the entries of each hand's action in the hand-pose modes (None: each
    joint's target or change, and the gap), the track a leaderboard reports it in (a keypose
    policy picks each hand's pose and the simulator moves the arm between them, a continuous
    one commands the arm every step, nothing in its action copied from the observation), and
    whether a recording writes it."""

    words: str
    hand_entries: int | None
    track: str
    recorded: bool = True


# What an environment's action is, one declaration a mode: joint targets, each joint's change
# from where it is (relative), each hand's pose change (ee), the pose each hand goes to
# (waypoint), that pose from the pick location, the arm's clear pose or its next target
# (anchored), each hand's bounded pose change from where it is measured (delta), or each
# hand's pose in the world bounded as a delta is (absolute). The last five are hand poses,
# turned into joints by the IK.
MODES: dict[str, ModeWords] = {
    "joint": ModeWords("joint targets", None, "continuous"),
    "relative": ModeWords(
        "relative (each joint's change from where it is: what a learner predicts most precisely)",
        None,
        "continuous",
    ),
    "ee": ModeWords("ee (each hand's pose change)", 5, "continuous", recorded=False),
    "waypoint": ModeWords("waypoint (the pose each hand goes to)", 5, "keypose"),
    "anchored": ModeWords(
        "anchored (that pose from the pick location, the arm's clear pose or its next target)",
        6,
        "keypose",
    ),
    "delta": ModeWords(
        "delta (each hand's pose change from where it is measured, bounded)", 5, "continuous"
    ),
    "absolute": ModeWords(
        "absolute (each hand's pose in the world, bounded as a delta is)", 5, "continuous"
    ),
}
ACTION_MODES = tuple(MODES)
ACTION_MODE_WORDS = {name: mode.words for name, mode in MODES.items()}
RECORD_ACTION_MODES = tuple(name for name, mode in MODES.items() if mode.recorded)
ACTION_MODE_HAND_ENTRIES = {name: mode.hand_entries for name, mode in MODES.items()}
ACTION_MODE_TRACKS = {name: mode.track for name, mode in MODES.items()}
# A dataset's frame rates, an environment's step rates (each divides the 100 Hz control).
FPS_CHOICES = (10, 20, 25, 50, 100)
# What a recording films by default, and at what size (height, width): lerobot's plugin
# evaluates with the same, so a default recording's checkpoint needs no more flags.
RECORD_CAMERAS: tuple[str, ...] = ("overview", "left_wrist", "right_wrist")
RECORD_IMAGE_SIZE = (224, 224)
RECORD_FPS = 25
# s a recording films after a build succeeds: the last brick's release and the hands leaving
# (an episode that ended at its success would teach the last release from a few frames).
RECORD_LINGER = 2.0
# The first seed an evaluation scores (recordings start at 0: the two never overlap).
EVAL_FIRST_SEED = 100_000
# The Gymnasium ids pyramid_sim registers when imported: its own keys, and lerobot's.
ENV_ID = "pyramid_sim/Build-v0"
LEROBOT_ENV_ID = "pyramid_sim/Lerobot-v0"


def in_words(options: Iterable[object]) -> str:
    """Options as a person reads them in an accepted range: `a, b or c`."""
    *rest, last = map(str, options)
    return f"{', '.join(rest)} or {last}" if rest else last


__all__ = [
    "in_words",
    "ACTION_MODES",
    "ACTION_MODE_WORDS",
    "ACTION_MODE_HAND_ENTRIES",
    "ACTION_MODE_TRACKS",
    "MODES",
    "ModeWords",
    "RECORD_ACTION_MODES",
    "FPS_CHOICES",
    "ENV_ID",
    "LEROBOT_ENV_ID",
    "DEFAULT_VARIATION",
    "EVAL_FIRST_SEED",
    "RECORD_CAMERAS",
    "RECORD_FPS",
    "RECORD_IMAGE_SIZE",
    "RECORD_LINGER",
    "ARMS",
    "ARM_CHOICES",
    "BACKENDS",
    "CAMERAS",
    "ROBOT_NAMES",
    "SCHEDULES",
    "VARIATIONS",
    "Arm",
    "ArmChoice",
    "Backend",
    "Camera",
    "RobotName",
    "Schedule",
]
