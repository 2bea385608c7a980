"""The Python API without physics: plans, settings and refusals (tests/physics/test_api_build.py
builds)."""

import numpy as np
import pytest

import pyramid_sim
from pyramid_sim.params import PARAMS


def test_plan_takes_a_structure_its_size_and_settings():
    plan = pyramid_sim.plan("wall", bricks=5, width=2, arms="left", brick_mass=0.7)
    assert plan.structure == "wall" and plan.arms == "left"
    assert len(plan.bricks) == 5 and {b.arm for b in plan.bricks} == {"left"}


def test_robot_and_schedule_are_settings():
    config = pyramid_sim.settings(robot="baxter", schedule="overlap", seed=4)
    assert (config.robot, config.schedule, config.seed) == ("baxter", "overlap", 4)
    with pytest.raises(pyramid_sim.ConfigError, match="schedule: unknown 'fast'"):
        pyramid_sim.settings(schedule="fast")


def test_every_table_parameter_is_a_setting():
    for p in PARAMS:
        value = (p.low + p.high) / 2
        assert p.read(pyramid_sim.settings(**{p.name: value})) == value


@pytest.mark.parametrize(
    "kwargs, words",
    [
        ({"stiffness": 3}, "unknown 'stiffness'; accepted friction, brick_mass"),
        ({"friction": 0}, "brick friction: 0 is out of range; accepted (0, 5]"),
        ({"brick_mass": float("nan")}, "brick mass (kg)"),
        ({"seed": -1}, "seed"),
        ({"layers": 0}, "layers"),
        ({"arms": "middle"}, "arms"),
    ],
)
def test_bad_settings_raise_one_config_error(kwargs, words):
    with pytest.raises(pyramid_sim.ConfigError) as err:
        pyramid_sim.plan("pyramid", **kwargs)
    assert words in str(err.value)
    assert isinstance(err.value, pyramid_sim.PyramidSimError)


def test_an_unknown_keyword_names_every_keyword_the_function_takes():
    with pytest.raises(pyramid_sim.ConfigError) as err:
        pyramid_sim.build("pyramid", colour=1)  # refused before any physics
    for name in (
        "friction",
        "schedule",
        "config",
        "layers",
        "goals",
        "arms",
        "video",
        "snapshot",
        "video_config",
    ):
        assert name in str(err.value).split("accepted", 1)[1]


@pytest.mark.parametrize(
    "call, words",
    [
        (lambda: pyramid_sim.plan("list", goals={"x": 0.7}),
         "goals: {'x': 0.7} is not a path; accepted a JSON or CSV file's path, as a str or Path"),
        (lambda: pyramid_sim.plan("pyramid", config="x"),
         "config: 'x' is not a SimConfig; accepted pyramid_sim.SimConfig(...) or None"),
        (lambda: pyramid_sim.build("pyramid", layers=1, video=b"x.mp4"),
         "mp4 path: b'x.mp4' is not a path; accepted a file's path ending in .mp4"),
        (lambda: pyramid_sim.build("pyramid", layers=1, snapshot=3),
         "png path: 3 is not a path; accepted a file's path ending in .png"),
        (lambda: pyramid_sim.build("pyramid", layers=1, out=3),
         "out: 3 is not a path; accepted a folder's path"),
        (lambda: pyramid_sim.build("pyramid", layers=1, on_placed=5),
         "on_placed: 5 cannot be called; accepted a function, or None"),
        (lambda: pyramid_sim.build("pyramid", layers=1, video_config="x"),
         "video_config: 'x' is not a VideoConfig; accepted pyramid_sim.VideoConfig(...)"),
    ],
)  # fmt: skip
def test_an_argument_of_the_wrong_kind_is_refused_naming_it_before_any_physics(call, words):
    """They were TypeError and AttributeError, or a callback's failure halfway through a
    build: one ConfigError naming the argument and what it takes, as the command line does."""
    with pytest.raises(pyramid_sim.ConfigError) as err:
        call()
    assert words in str(err.value)


def test_numpy_numbers_are_numbers():
    """np.int64(2) layers were "out of range" and np.float32(0.5) friction "not a number";
    they reach the settings as Python's own, which JSON writes."""
    plan = pyramid_sim.plan("pyramid", layers=np.int64(2), friction=np.float32(0.5))
    assert len(plan.bricks) == 3 and type(plan.spec.layers) is int
    config = pyramid_sim.settings(friction=np.float32(0.5), seed=np.int64(3))
    assert (config.brick.friction, config.seed) == (0.5, 3)
    assert type(config.brick.friction) is float and type(config.seed) is int
    with pytest.raises(pyramid_sim.ConfigError, match="layers: 99 is out of range"):
        pyramid_sim.plan("pyramid", layers=np.int64(99))


def test_build_refuses_a_wrong_video_suffix_before_any_physics():
    with pytest.raises(pyramid_sim.ConfigError, match="must end in .mp4"):
        pyramid_sim.build("pyramid", layers=1, video="out/build.avi")


@pytest.mark.parametrize(
    "kwargs, flags",
    [
        ({"friction": -1}, ["--friction", "-1"]),
        ({"brick_mass": float("nan")}, ["--brick-mass", "nan"]),
        ({"layers": 99}, ["--layers", "99"]),
        ({"grip_force": 0}, ["--grip-force", "0"]),
    ],
)
def test_a_bad_value_reads_the_same_through_the_api_as_on_the_command_line(kwargs, flags, refused):
    with pytest.raises(pyramid_sim.ConfigError) as err:
        pyramid_sim.plan("pyramid", **kwargs)
    line = refused(["plan", "--structure", "pyramid", *flags])
    assert line.strip() == f"pyramid-sim: error: {err.value}"


def test_the_hand_speed_cap_is_the_robot_at_hands():
    """Baxter's hand moves at most 0.3 m/s; the cap comes with the robot, so a config made for
    Baxter and switched to the Panda moves at the Panda's speeds, and result.json records the
    speeds moved by."""
    from pyramid_sim.output.judge import inputs_of

    switched = pyramid_sim.settings(config=pyramid_sim.SimConfig(robot="baxter"), robot="panda")
    assert (switched.hand_motion.speed, switched.hand_motion.turn_rate) == (0.6, 1.5)
    baxter = pyramid_sim.SimConfig(robot="baxter")
    hand = baxter.hand_motion
    assert (hand.speed, hand.slow_speed, hand.turn_rate) == (0.3, 0.15, 0.75)
    recorded = inputs_of(pyramid_sim.plan("pyramid", layers=1, robot="baxter"), baxter)
    assert recorded.settings["motion"]["speed"] == 0.3


def test_a_slow_motion_the_loop_cannot_film_is_refused(refused):
    """The loop films at most one frame a 2 ms physics step: 0.1 at 120 fps (a frame every
    0.83 ms) is refused, by the API and the command line alike, before any physics."""
    vc = pyramid_sim.VideoConfig(fps=120, speedup=0.1)
    with pytest.raises(pyramid_sim.ConfigError, match="less than the 2 ms physics step") as err:
        pyramid_sim.build("pyramid", layers=1, video="x/b.mp4", video_config=vc)
    assert "accepted 0.24 to 100 at 120 fps" in str(err.value)
    line = refused(
        [
            "build",
            "--structure",
            "pyramid",
            "--layers",
            "1",
            "--video",
            "x/b.mp4",
            "--fps",
            "120",
            "--speedup",
            "0.1",
        ]
    )
    assert line.strip() == f"pyramid-sim: error: {err.value}"


@pytest.mark.parametrize("interval", [0, 5, 2.5, True])
def test_the_free_ik_interval_is_a_whole_number_of_control_steps(interval):
    from pyramid_sim.config import MotionConfig

    with pytest.raises(pyramid_sim.ConfigError) as err:
        MotionConfig(free_ik_interval=interval)
    assert str(err.value) == (
        f"free IK interval: {interval!r} is out of range; accepted 1 to 4, whole numbers"
    )
