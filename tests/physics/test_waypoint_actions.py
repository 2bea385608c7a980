"""action_mode="waypoint": each hand's pose to go to, the arm moved there by the ee mode's IK
through the motion generator, no faster than the hand's speeds."""

import json

import gymnasium
import numpy as np
import pyarrow.parquet as pq
import pytest
from gymnasium.utils.env_checker import check_env

import pyramid_sim
from pyramid_sim.learning.action_modes import waypoint
from pyramid_sim.learning.recording.episode import JointNoise

ENV = pyramid_sim.ENV_ID


def _env(**options):
    return gymnasium.make(
        ENV, structure="pyramid-even", layers=1, variation="layout", action_mode="waypoint",
        **options,
    ).unwrapped  # fmt: skip


def test_the_experts_waypoints_build_and_the_checker_passes():
    env = _env()
    assert env.action_space.shape == (10,)
    assert env.action_units.names[:5] == ("left/x", "left/y", "left/z", "left/yaw", "left/gripper")
    check_env(env, skip_render_check=True)
    env.reset(seed=3)
    rewards, gaps = 0.0, set()
    while True:
        action = env.expert_action()
        gaps |= {float(action[4]), float(action[9])}
        _, reward, terminated, truncated, info = env.step(action)
        rewards += reward
        if terminated or truncated:
            break
    assert terminated and info["is_success"] and rewards == 2, info["failure"]
    assert gaps == {0.0, np.float32(env.mode.control.hands.open)}  # open or closed, never between
    env.close()


def test_a_waypoint_is_where_the_move_ends_not_the_next_step_of_it():
    """Through a move the expert's action stays at the move's end (aimed as its loop aims)
    while the hand travels; a relative or ee label would change every step."""
    env = _env()
    env.reset(seed=0)
    runner = env.loop.dispatch.runners["left"]
    labels, tools = [], []
    for _ in range(400):
        action = env.expert_action()
        step = runner.current
        if step is not None and step.name == "approach" and runner.started:
            labels.append(action[:3].copy())
            tools.append(env.loop.data.site_xpos[env.loop.handles.tcp_site["left"]].copy())
            aimed = env.loop.closure.aim("left", step.pose)
            np.testing.assert_allclose(action[:3], aimed.position, atol=1e-6)
        env.step(action)
    assert len(labels) >= 3
    travel = np.linalg.norm(tools[-1] - tools[0])
    assert travel > 0.01  # the hand moves on while the label holds (only the aim creeps)
    assert np.linalg.norm(np.ptp(np.array(labels), axis=0)) < travel / 2
    env.close()


def test_a_far_waypoint_moves_the_target_no_faster_than_the_hand_moves():
    """A waypoint 30 cm off: each control step the tool's target moves at most the hand's
    free speed times the control step; the arm follows within its limits."""
    env = _env()
    env.reset(seed=0)
    hand = env.mode.control
    start = hand.ee.targets["left"]
    action = hand.hold(env.loop).astype(np.float32)
    action[1] -= 0.3  # left hand 30 cm towards the middle
    way = []
    for _ in range(10):
        before = hand.ee.targets["left"]
        env.step(action)
        after = hand.ee.targets["left"]
        way.append(np.linalg.norm(after.position - before.position))
    most = hand.speed * hand.dt * env.control_steps
    assert max(way) <= most + 1e-9  # (the ee mode's leash may hold it back further)
    assert hand.ee.targets["left"].y < start.y - 0.1  # and it does move
    env.loop.monitor.flush()
    assert env.loop.monitor.speed_ratio < 1.0 and env.loop.monitor.torque_ratio < 1.0
    env.close()


@pytest.mark.parametrize("robot", ["panda", "baxter"])
def test_baxters_waypoint_gains_and_sheds_its_speed_gently_the_pandas_at_once(robot):
    """Baxter's shoulder has too little torque to spare for the Panda's step starts and stops
    (docs/notes/2026-11-28-baxter-holding.md): its target's speed changes by at
    most its hand acceleration a control step, and its motion generator accelerates the
    joints at a quarter of their limits; the Panda's target is at full speed in the first
    step, its generator at half."""
    from pyramid_sim.physics.motion_generator import ACCELERATION_SHARE

    env = _env(robot=robot)
    env.reset(seed=0)
    hand, robot_description = env.mode.control, env.loop.config.robot_description
    action = hand.hold(env.loop).astype(np.float32)
    action[1] -= 0.2  # left hand 20 cm towards the middle
    positions = [hand.ee.targets["left"].position]
    for _ in range(15):
        env.step(action)
        positions.append(hand.ee.targets["left"].position)
    speeds = np.linalg.norm(np.diff(positions, axis=0), axis=1) / (hand.dt * env.control_steps)
    joints = env.generator.limits.acceleration[~env.generator.limits.fingers]
    limits = np.concatenate([a.acceleration_limits for a in robot_description.arms.values()])
    if robot == "panda":
        assert speeds[0] > 0.5 * hand.speed  # (the leash may hold it back a little)
        assert joints == pytest.approx(ACCELERATION_SHARE * limits)
        return
    gained = hand.acceleration * hand.dt * env.control_steps  # the most an env step adds
    assert speeds[0] <= gained + 1e-9 and np.all(np.diff(speeds) <= gained + 1e-9)
    assert speeds.max() > 0.8 * hand.speed  # and it does get up to speed
    assert joints == pytest.approx(0.25 * limits)
    env.loop.monitor.flush()
    assert env.loop.monitor.torque_ratio < 1.0
    env.close()


def test_a_jittering_waypoint_is_smoothed_and_still_builds():
    """2 mm of white noise on each hand's waypoint every step, as a learner's errors: the lag
    at a move's end and the generator keep the brick in the fingers."""
    env = _env()
    env.reset(seed=0)
    noise = np.random.default_rng(0)
    while True:
        action = env.expert_action()
        for arm in (0, 5):
            action[arm : arm + 3] += noise.normal(0.0, 0.002, 3)
        _, _, terminated, truncated, info = env.step(action.astype(np.float32))
        if terminated or truncated:
            break
    assert info["is_success"], info["failure"]
    env.close()


def test_without_the_lag_a_waypoint_is_met_at_full_speed(monkeypatch):
    """The lag is what slows a move at its end: with it gone the last step before the
    waypoint is a full slow-speed step, with it a fraction of one."""
    env = _env()
    env.reset(seed=0)

    def last_step() -> float:
        action = env.mode.control.hold(env.loop).astype(np.float32)
        action[2] += 0.005  # 5 mm up
        before = env.mode.control.ee.targets["left"].z
        env.mode.control.command(env.loop, action)
        return env.mode.control.ee.targets["left"].z - before

    lagged, lag = last_step(), waypoint.LAG
    monkeypatch.setattr(waypoint, "LAG", 1e-9)
    env.reset(seed=0)
    unlagged = last_step()
    assert unlagged == pytest.approx(env.mode.control.slow_speed * env.mode.control.dt, rel=1e-4)
    assert lagged == pytest.approx(0.005 / lag * env.mode.control.dt, rel=1e-4)
    assert lagged < unlagged
    env.close()


def test_darts_noise_on_waypoints_moves_the_hands_positions_only():
    env = _env()
    env.reset(seed=0)
    noise = JointNoise(env, 0, 0.01)
    action = env.expert_action()
    moved = noise(action) - action
    assert np.all(moved[[0, 1, 2, 5, 6, 7]] != 0)  # x, y, z of each hand
    assert np.all(moved[[3, 4, 8, 9]] == 0)  # not the yaw, not the fingers
    env.close()


def test_a_waypoint_recording_names_its_actions_and_replays_into_its_build(tmp_path, replay):
    root = tmp_path / "d"
    recorded = pyramid_sim.record(
        "pyramid-even", out=root, layers=1, episodes=1, cameras=(), action_mode="waypoint",
        variation="layout",
    )  # fmt: skip
    assert recorded.failed == ()
    info = json.loads((root / "meta/info.json").read_text())
    assert info["features"]["action"]["names"][5:8] == ["right/x", "right/y", "right/z"]
    frames = pq.read_table(root / "data/chunk-000/file-000.parquet").to_pydict()
    actions = np.array(frames["action"])
    env = _env()
    terminated, info = replay(env, actions)
    assert terminated and info["is_success"]
    env.close()


def test_a_gap_left_between_open_and_closed_closes_the_hand_to_the_servos():
    """A learner's gap a little short of open still commands the finger servo closed (its
    force limit then squeezes): read from the compiled model's controls and finger joints."""
    env = _env()
    obs, _ = env.reset(seed=0)
    hands, gaps = env.mode.control.hands, env.mode.control.ee.gaps
    opened = obs["state"][gaps]
    action = env.mode.control.hold(env.loop)
    action[4] = hands.threshold - 0.002  # the left hand: closed; the right stays open
    for _ in range(env.fps):  # a second: the motion generator limits the fingers' speed too
        obs, *_ = env.step(action.astype(np.float32))
    ctrl = env.loop.data.ctrl[env.loop.handles.ctrl_index][gaps]
    fingers = obs["state"][gaps]
    assert ctrl[0] == pytest.approx(0.0, abs=1e-9) and ctrl[1] == pytest.approx(hands.open)
    assert fingers[0] < 0.5 * opened[0] and fingers[1] == pytest.approx(opened[1], abs=1e-3)
    env.close()
