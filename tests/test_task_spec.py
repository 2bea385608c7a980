"""The task spec (learning/task/spec.py): an episode's options checked once, where the spec
is made, each refusal a ConfigError naming the field and what it accepts; and every caller
(gym.make, the API's record, lerobot's plugin config, the command line) refusing through it.
No physics: a spec is checked before MuJoCo is imported."""

import inspect
import re
from dataclasses import fields, replace
from types import SimpleNamespace

import pytest

import pyramid_sim
from pyramid_sim.errors import ConfigError
from pyramid_sim.learning.lerobot_plugin.plugin_task import plugin_task, step_limit_given
from pyramid_sim.learning.task.spec import ACCEPTED, SETTINGS, TaskSpec


@pytest.mark.parametrize(
    ("keywords", "message"),
    [
        ({"brick_poses": "no"}, "brick poses: 'no' is not a bool; accepted True or False"),
        ({"all_goals": 1}, "all goals: 1 is not a bool; accepted True or False"),
        ({"limit_commands": None}, "limit commands: None is not a bool"),
        ({"randomize": "friction"}, "randomize: 'friction' is one name, not a sequence"),
        ({"randomize": ("friction", "wind")}, "randomize: unknown 'wind'; accepted all, none"),
        ({"cameras": "overview"}, "cameras: 'overview' is one name, not a sequence"),
        ({"cameras": ("nose",)}, "cameras: unknown 'nose'; accepted overview, front, top"),
        ({"fps": 30}, "fps: 30; accepted 10, 20, 25, 50, 100"),
        ({"linger": -1}, "linger: -1 is out of range; accepted [0, 10]"),
        ({"image_size": (0, 0)}, "image size: (0, 0); accepted (height, width)"),
        ({"width": 7}, "image size: (480, 7); accepted (height, width)"),
        ({"camera_name": "nose"}, "cameras: unknown 'nose'"),
        ({"action_mode": "torque"}, "action mode: unknown 'torque'; accepted joint"),
        ({"render_mode": "human"}, "render mode: unknown 'human'; accepted rgb_array"),
        ({"arms": "all"}, "arms: unknown 'all'; accepted both, left or right"),
        ({"variation": "wild"}, "variation: unknown 'wild'; accepted fixed, layout, full"),
        ({"layers": 99}, "layers: 99 is out of range"),
        ({"friction": -1.0}, "brick friction: -1 is out of range; accepted (0, 5]"),
        ({"robot": "kuka"}, "robot: unknown 'kuka'"),
    ],
)
def test_each_field_is_checked_where_the_spec_is_made(keywords, message):
    with pytest.raises(ConfigError, match="^" + _escaped(message)):
        TaskSpec.of("pyramid-even", **keywords)


def _escaped(text: str) -> str:
    return re.escape(text)


def test_an_unknown_keyword_names_every_one_accepted():
    """gym.make's list was seven short: now every field and setting is named."""
    with pytest.raises(ConfigError) as error:
        TaskSpec.of("pyramid-even", flavour="x")
    text = str(error.value)
    assert text.startswith("keyword: unknown 'flavour'; accepted ")
    named = set(text.split("accepted ", 1)[1].split(", "))
    assert named == set(ACCEPTED)
    assert {f.name for f in fields(TaskSpec)} - {"settings"} <= named
    assert set(SETTINGS) <= named and "robot" in named


@pytest.mark.physics  # gym.make imports the environment's module, which loads MuJoCo
def test_gym_make_refuses_through_the_spec_before_any_physics():
    import gymnasium

    with pytest.raises(ConfigError, match="brick poses: 'no' is not a bool"):
        gymnasium.make(pyramid_sim.ENV_ID, structure="pyramid", brick_poses="no")
    with pytest.raises(ConfigError, match="keyword: unknown 'flavour'; accepted structure"):
        gymnasium.make(pyramid_sim.ENV_ID, structure="pyramid", flavour="x")


def test_a_spec_is_taken_whole_and_changed_only_by_replace():
    spec = TaskSpec.of("pyramid", layers=1, fps=10, randomize=("none",), friction=0.8)
    assert TaskSpec.of(spec) is spec
    assert spec.randomize == () and spec.settings == {"friction": 0.8}
    config, structure = spec.resolved()
    assert config.brick.friction == 0.8 and structure.size == {"layers": 1}
    with pytest.raises(ConfigError, match="keywords: fps beside a whole TaskSpec"):
        TaskSpec.of(spec, fps=25)
    with pytest.raises(ConfigError, match="fps: 7"):
        replace(spec, fps=7)  # the checks run again on a changed spec
    assert replace(spec, fps=25).fps == 25


def test_every_field_says_what_it_is():
    """A field's doc is its flag's help: none is left without one."""
    assert all(f.metadata.get("doc") for f in fields(TaskSpec))


def test_the_api_record_takes_a_spec_and_few_parameters(tmp_path):
    assert len(inspect.signature(pyramid_sim.record).parameters) <= 8
    out = tmp_path / "d"
    for keywords, message in (
        ({"repair": "no"}, "repair: 'no' is not a bool"),
        ({"beta": 0.3}, "beta: 0.3 without a policy drives nothing"),
        ({"brick_poses": "no"}, "brick poses: 'no' is not a bool"),
        ({"flavour": 1}, "keyword: unknown 'flavour'; accepted structure"),
    ):
        with pytest.raises(ConfigError, match=_escaped(message)):
            pyramid_sim.record("pyramid", out=out, **keywords)
    with pytest.raises(ConfigError, match="beside a whole TaskSpec"):
        pyramid_sim.record(TaskSpec("pyramid"), out=out, fps=10)
    assert not out.exists()  # refused before anything was written


def _plugin_config(**changed) -> SimpleNamespace:
    fields_ = {
        "task": "pyramid-even",
        "layers": 1,
        "robot": "baxter",
        "variation": "layout",
        "fps": 25,
        "cameras": ("overview",),
        "observation_height": 224,
        "observation_width": 224,
        "action_mode": "joint",
        "brick_poses": True,
        "all_goals": True,
    }
    return SimpleNamespace(**{**fields_, **changed})


def test_the_plugins_config_is_checked_as_a_spec():
    spec = plugin_task(_plugin_config())
    assert spec.render_mode == "rgb_array" and spec.image_size == (224, 224)
    with pytest.raises(ConfigError, match="brick poses: 'no' is not a bool"):
        plugin_task(_plugin_config(brick_poses="no"))
    with pytest.raises(ConfigError, match="cameras: unknown 'nose'"):
        plugin_task(_plugin_config(cameras=["nose"]))
    for bad in (-5, 0, 2.5, True):
        with pytest.raises(ConfigError, match="episode length: .*; accepted 1 to"):
            step_limit_given(bad)
    assert step_limit_given(2250) == 2250


def test_record_beta_without_policy_is_one_line(refused, tmp_path):
    err = refused(["record", "--beta", "0.3", "--out", str(tmp_path / "d"), "--quiet"])
    assert "beta: 0.3 without a policy drives nothing" in err
    assert not (tmp_path / "d").exists()


def test_each_leaderboard_row_builds_its_task_spec():
    """A recipe (benchmarks/rows.py) makes its task as a spec, checked as every caller's."""
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
    from rows import ROWS

    for recipe in ROWS.values():
        spec = recipe.task
        assert (spec.structure, spec.layers, spec.fps) == (
            recipe.structure,
            recipe.layers,
            recipe.fps,
        )
        assert spec.brick_poses == recipe.brick_poses and spec.cameras == recipe.cameras
    with pytest.raises(ConfigError, match="brick poses: 'no' is not a bool"):
        _ = replace(ROWS["panda-2"], brick_poses="no").task
