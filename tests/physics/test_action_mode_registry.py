"""Every action mode's name the environment accepts has its class in the registry, and each
says its size for every robot."""

import pytest

from pyramid_sim.choices import (
    ACTION_MODE_HAND_ENTRIES,
    ACTION_MODE_TRACKS,
    ACTION_MODE_WORDS,
    ACTION_MODES,
    RECORD_ACTION_MODES,
    ROBOT_NAMES,
)
from pyramid_sim.errors import ConfigError
from pyramid_sim.learning.action_modes.registry import MODES, action_size, mode_class
from pyramid_sim.learning.lerobot_plugin.checkpoint_inputs import action_entries
from pyramid_sim.robots import robot


def test_every_mode_name_has_its_class():
    assert tuple(MODES) == ACTION_MODES  # the CLI's choices (choices.py imports no MuJoCo)
    assert set(ACTION_MODE_WORDS) == set(MODES)  # and their help
    assert set(RECORD_ACTION_MODES) <= set(MODES)
    with pytest.raises(
        ConfigError, match="accepted joint, relative, ee, waypoint, anchored, delta or absolute"
    ):
        mode_class("torque")


@pytest.mark.parametrize("name", ROBOT_NAMES)
def test_each_mode_says_its_size(name):
    """What lerobot's plugin declares: the joint modes a command's entries (each arm's joints
    and gap), the hand modes five a hand (x, y, z, yaw, gap), anchored six (and the anchor)."""
    pair = robot(name)
    motors = sum(len(arm.joints) + 1 for arm in pair.arms.values())
    sizes = {mode: action_size(mode, pair) for mode in MODES}
    assert sizes == {"joint": motors, "relative": motors, "ee": 10, "waypoint": 10, "anchored": 12,
                     "delta": 10, "absolute": 10}  # fmt: skip
    # what the checkpoint reader and the leaderboard know of the modes without MuJoCo
    assert sizes == {mode: action_entries(name, mode) for mode in MODES}
    assert set(ACTION_MODE_TRACKS) == set(ACTION_MODE_HAND_ENTRIES) == set(MODES)
