"""A lerobot checkpoint is evaluated as it was trained: with the cameras it saw at their size,
read from its config.json (a checkpoint without images, or a named policy, asks for none), and
on the robot, structure, size, variation, rate and action mode its training saw where they are
not given; a given one that contradicts them is refused naming both, and a checkpoint that
does not say is refused naming the flags it needs."""

import json

import pytest

import pyramid_sim
from pyramid_sim.errors import ConfigError
from pyramid_sim.learning.lerobot_plugin.checkpoint_inputs import (
    DEFAULTS,
    Task,
    action_entries,
    checkpoint_task,
    checkpoint_views,
)


def _checkpoint(folder, features):
    folder.mkdir()
    (folder / "config.json").write_text(json.dumps({"type": "act", "input_features": features}))
    return str(folder)


def test_the_cameras_and_their_size_are_read_from_the_checkpoint(tmp_path):
    features = {
        "observation.state": {"type": "STATE", "shape": [16]},
        "observation.images.overview": {"type": "VISUAL", "shape": [3, 96, 128]},
        "observation.images.left_wrist": {"type": "VISUAL", "shape": [3, 96, 128]},
    }
    views = checkpoint_views(_checkpoint(tmp_path / "c", features))
    assert views == {"cameras": ("overview", "left_wrist"), "image_size": (96, 128)}


def test_no_cameras_are_asked_for_without_images_or_a_checkpoint(tmp_path):
    state = {"observation.state": {"type": "STATE", "shape": [16]}}
    assert checkpoint_views(_checkpoint(tmp_path / "c", state)) == {}
    assert checkpoint_views("expert") == {}
    assert checkpoint_views(str(tmp_path)) == {}  # a folder with no config.json


def test_cameras_of_different_sizes_are_refused(tmp_path):
    features = {
        "observation.images.overview": {"type": "VISUAL", "shape": [3, 96, 96]},
        "observation.images.left_wrist": {"type": "VISUAL", "shape": [3, 64, 64]},
    }
    with pytest.raises(ConfigError, match=r"cameras see \[\(64, 64\), \(96, 96\)\]"):
        checkpoint_views(_checkpoint(tmp_path / "c", features))


def test_an_unreadable_config_is_one_line(tmp_path):
    (tmp_path / "c").mkdir()
    (tmp_path / "c" / "config.json").write_text("{not json")
    with pytest.raises(ConfigError, match="cannot be read"):
        checkpoint_views(str(tmp_path / "c"))


def test_what_is_not_given_is_what_training_saw(tmp_path, checkpoint, recording):
    demos = recording(tmp_path / "demos")
    folder = checkpoint(tmp_path / "c", dataset=demos)
    assert checkpoint_task(folder, Task()) == Task(
        "panda", "pyramid-even", {"layers": 1}, "layout", 10, "anchored"
    )
    agreeing = Task("panda", "pyramid-even", {"layers": 1}, None, 10, "anchored")
    assert checkpoint_task(folder, agreeing) == checkpoint_task(folder, Task())


def test_another_variation_is_a_test_of_other_episodes_not_a_contradiction(
    tmp_path, checkpoint, recording
):
    """docs/benchmark.md's robustness probe: the layout-trained policy scored at `full`."""
    folder = checkpoint(tmp_path / "c", dataset=recording(tmp_path / "demos"))
    assert checkpoint_task(folder, Task(variation="full")).variation == "full"


@pytest.mark.parametrize(
    "given, words",
    [(Task(fps=25), "fps: 25 given, but the checkpoint was trained with 10"),
     (Task(action_mode="joint"), "action mode: joint given, but the checkpoint was trained "
      "with anchored"),
     (Task(robot="so101"), "robot: so101 given, but the checkpoint was trained with panda"),
     (Task(structure="pyramid"), "structure: pyramid given, but the checkpoint was trained "
      "with pyramid-even"),
     (Task(size={"layers": 2}), "layers: 2 given, but the checkpoint was trained with 1")],
)  # fmt: skip
def test_a_given_value_that_contradicts_training_is_refused_naming_both(
    tmp_path, checkpoint, recording, given, words
):
    demos = recording(tmp_path / "demos")
    folder = checkpoint(tmp_path / "c", dataset=demos)
    with pytest.raises(ConfigError, match=words) as refused:
        checkpoint_task(folder, given)
    assert f"(read from its dataset {str(demos)!r}); accepted" in str(refused.value)


def test_a_checkpoint_that_does_not_say_needs_its_mode_and_rate_given(tmp_path, checkpoint):
    folder = checkpoint(tmp_path / "c", train=False)
    with pytest.raises(ConfigError) as refused:
        checkpoint_task(folder, Task())
    line = str(refused.value)
    assert line.startswith(f"policy: {folder!r} does not say how it was trained")
    assert "accepted --action-mode anchored (what its 12 actions fit) and --fps (10, 20" in line
    with pytest.raises(ConfigError, match="accepted --fps \\(10, 20, 25, 50 or 100"):
        checkpoint_task(folder, Task(action_mode="anchored"))
    settled = checkpoint_task(folder, Task(action_mode="anchored", fps=10))
    assert settled == Task("panda", "pyramid-even", {}, "layout", 10, "anchored")


def test_an_so101_action_fits_three_modes_and_each_is_named(tmp_path, checkpoint):
    folder = checkpoint(tmp_path / "c", action=12, state=12, train=False)
    with pytest.raises(ConfigError, match="--action-mode joint, relative or anchored"):
        checkpoint_task(folder, Task(robot="so101"))


def test_a_mode_whose_width_is_not_the_actions_is_refused(tmp_path, checkpoint):
    """What a user met as `operands could not be broadcast together with shapes
    (12,) (16,)` after the first step: now one line before anything runs."""
    folder = checkpoint(tmp_path / "c", action=12, train=False)
    with pytest.raises(
        ConfigError,
        match="action mode: joint acts with 16 entries on panda, but the checkpoint's action "
        "has 12; accepted anchored",
    ):
        checkpoint_task(folder, Task(action_mode="joint", fps=10))
    wide = checkpoint(tmp_path / "w", action=14, train=False)
    with pytest.raises(ConfigError, match="accepted its robot's \\(none of panda's modes has 14"):
        checkpoint_task(wide, Task(action_mode="joint", fps=10))


def test_the_action_widths_are_the_plugins():
    modes = ("joint", "relative", "waypoint", "anchored")
    assert [action_entries("panda", m) for m in modes] == [16, 16, 10, 12]
    assert action_entries("so101", "joint") == 12 and action_entries("panda", "ee") == 10


def test_a_policy_that_is_no_checkpoint_takes_the_defaults(tmp_path):
    assert checkpoint_task("expert", Task()) == DEFAULTS
    assert checkpoint_task(str(tmp_path), Task(fps=50)).fps == 50  # no config.json: none


def test_the_api_refuses_a_contradiction_before_anything_runs(tmp_path, checkpoint, recording):
    folder = checkpoint(tmp_path / "c", dataset=recording(tmp_path / "demos"))
    with pytest.raises(ConfigError, match="fps: 25 given"):
        pyramid_sim.evaluate(folder, fps=25, out=tmp_path / "never")
    assert not (tmp_path / "never").exists()


@pytest.mark.parametrize(
    "flags, words",
    [(["--fps", "25"], "fps: 25 given, but the checkpoint was trained with 10"),
     (["--action-mode", "relative"], "action mode: relative given"),
     (["--layers", "2"], "layers: 2 given, but the checkpoint was trained with 1")],
)  # fmt: skip
def test_the_command_refuses_a_contradicting_flag_in_one_line(
    tmp_path, checkpoint, recording, refused, flags, words
):
    folder = checkpoint(tmp_path / "c", dataset=recording(tmp_path / "demos"))
    out = tmp_path / "never"
    line = refused(["evaluate", "--policy", folder, *flags, "--out", str(out)])
    assert line.startswith(f"pyramid-sim: error: {words}") and not out.exists()


def test_the_command_names_the_flags_a_checkpoint_that_does_not_say_needs(
    tmp_path, checkpoint, refused
):
    folder = checkpoint(tmp_path / "c", action=10, train=False)
    line = refused(["evaluate", "--policy", folder, "--out", str(tmp_path / "never")])
    assert (
        "accepted --action-mode waypoint, delta or absolute (what its 10 actions fit) and --fps"
        in line
    )
    assert not (tmp_path / "never").exists()


def test_a_policy_that_saw_each_arms_next_goal_alone_meets_any_size(
    tmp_path, checkpoint, recording
):
    """Its input is the same for every size of the structure: trained on six bricks, it is
    evaluated on twenty as asked (and in its observation's variant); one that saw every goal
    is refused another size."""
    demos = recording(tmp_path / "demos", size={"layers": 2}, all_goals=False, brick_poses=False)
    folder = checkpoint(tmp_path / "c", dataset=demos)
    task = checkpoint_task(folder, Task(size={"layers": 4}))
    assert task.size == {"layers": 4} and task.structure == "pyramid-even"
    assert checkpoint_views(folder) == {"brick_poses": False, "all_goals": False}
    seen = checkpoint(tmp_path / "s", dataset=recording(tmp_path / "all", size={"layers": 2}))
    with pytest.raises(ConfigError, match="layers: 4 given, but the checkpoint was trained with 2"):
        checkpoint_task(seen, Task(size={"layers": 4}))
