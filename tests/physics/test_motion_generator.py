"""The motion generator between a policy's targets and the servos: its command never moves
faster, accelerates harder or jerks more than its limits, never overshoots a target, and
arrives there at rest; the robot's limits and the action mode's jerk time reach it; bad limits
are refused."""

import numpy as np
import pytest

from pyramid_sim.physics.motion_generator import (
    ACCELERATION_SHARE,
    JERK_TIME,
    JOINT_JERK_TIME,
    MotionGenerator,
    MotionLimits,
    motion_limits,
)
from pyramid_sim.robots import robot

DT = 0.01


def _limits(n: int = 3) -> MotionLimits:
    ones = np.ones(n)
    return MotionLimits(2 * ones, 2 * ones, 10 * ones, 200 * ones, np.zeros(n, dtype=bool))


def _run(generator: MotionGenerator, targets: list[np.ndarray], steps: int) -> np.ndarray:
    path = [generator.position.copy()]
    for k in range(steps):
        path.append(generator.step(targets[min(k, len(targets) - 1)]).copy())
    return np.array(path)


def test_a_far_target_is_reached_at_rest_within_speed_acceleration_and_jerk():
    limits = _limits()
    generator = MotionGenerator(limits, DT)
    generator.reset(np.zeros(3))
    target = np.array([1.0, -0.5, 0.2])
    path = _run(generator, [target], 300)
    speed = np.diff(path, axis=0) / DT
    acceleration = np.diff(speed, axis=0) / DT
    jerk = np.diff(acceleration, axis=0) / DT
    assert np.abs(speed).max() <= 2.0 + 1e-6
    assert np.abs(acceleration).max() <= 10.0 + 1e-3
    assert np.abs(jerk).max() <= 200.0 * 1.01  # sampled at DT: within a rounding of it
    assert np.allclose(path[-1], target) and not generator.velocity.any()
    assert generator.lag() == pytest.approx(0.0, abs=1e-9)


def test_a_jittering_or_jumping_target_is_never_overshot():
    """A chunked gait (the target held, then a jump) and white noise on it: the command stays
    within the span of the targets it was given."""
    generator = MotionGenerator(_limits(1), DT)
    generator.reset(np.zeros(1))
    rng = np.random.default_rng(0)
    chunks = [np.array([0.05 * (k // 5)]) for k in range(100)]  # held 5 steps, then a jump
    noisy = [c + rng.normal(0, 0.002, 1) for c in chunks]
    path = _run(generator, noisy, 100)
    assert path.max() <= max(t.max() for t in noisy) + 1e-9 and path.min() >= -1e-9
    assert 0.0 < generator.lag() < 0.1  # behind the last target, not ahead of it


def test_the_robots_limits_reach_the_generator():
    panda = robot("panda")
    limits = motion_limits(panda, close_time=0.35)
    joints = len(panda.arms["left"].joints)
    assert len(limits.speed) == 2 * (joints + 1) and limits.fingers.sum() == 2
    left = panda.arms["left"]
    assert limits.acceleration[:joints] == pytest.approx(
        ACCELERATION_SHARE * np.array(left.acceleration_limits)
    )
    assert np.all(limits.speed[:joints] < np.array(left.velocity_limits))
    gap = joints  # the fingers open faster than they close
    assert (
        limits.speed[gap] > limits.falling[gap] == pytest.approx(2 * 2 * panda.finger_stroke / 0.35)
    )


@pytest.mark.parametrize("jerk_time", [JERK_TIME, JOINT_JERK_TIME])
def test_the_jerk_time_reaches_the_command(jerk_time):
    """Every entry toward a far target from rest: the command's jerk, read off its path, comes
    up to acceleration / `jerk_time` and never past it."""
    limits = motion_limits(robot("panda"), close_time=0.35, jerk_time=jerk_time)
    generator = MotionGenerator(limits, DT)
    generator.reset(np.zeros(len(limits.speed)))
    path = _run(generator, [np.where(limits.fingers, 0.03, 0.5)], 400)
    peak = np.abs(np.diff(path, n=3, axis=0) / DT**3).max(axis=0)
    most = limits.acceleration / jerk_time
    assert np.all(peak <= most * 1.01)
    assert np.all(peak[limits.fingers] >= 0.9 * most[limits.fingers])
    assert np.any(peak[~limits.fingers] >= 0.9 * most[~limits.fingers])  # the one that paces


def test_the_joint_modes_filter_the_policys_targets_harder_than_the_hand_modes():
    """Straight from a policy to the generator (joint, relative) the jerk is reached in
    JOINT_JERK_TIME; behind the IK (the hand modes) in JERK_TIME."""
    from pyramid_sim.learning.env.env import BuildEnv

    for mode, jerk_time in [("joint", JOINT_JERK_TIME), ("relative", JOINT_JERK_TIME),
                            ("anchored", JERK_TIME), ("ee", JERK_TIME)]:  # fmt: skip
        limits = BuildEnv("pyramid-even", layers=1, action_mode=mode).generator.limits
        assert limits.jerk == pytest.approx(limits.acceleration / jerk_time), mode


@pytest.mark.parametrize("field", ["speed", "falling", "acceleration", "jerk"])
@pytest.mark.parametrize("value", [0.0, -1.0, np.inf])
def test_a_limit_that_is_not_positive_and_finite_is_refused(field, value):
    good = _limits(2)
    values = {f: getattr(good, f).copy() for f in ("speed", "falling", "acceleration", "jerk")}
    values[field][1] = value
    with pytest.raises(ValueError, match=f"motion limits: {field} must be positive"):
        MotionLimits(**values, fingers=good.fingers)
