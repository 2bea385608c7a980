"""The build as a Gymnasium environment: it passes Gymnasium's own checker, the scripted
expert rolled out in it builds what `build` builds, the same seed gives the same episode and
an unseeded reset the next, random actions end an episode with a reason rather than an error,
and two environments step side by side in an AsyncVectorEnv."""

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import pyramid_sim

ENV = pyramid_sim.ENV_ID


def _rollout(env, seed: int, steps: int | None = None):
    """The expert's episode from `seed`: every observation's state and bricks, rewards, and
    the last step's flags and info."""
    obs, _ = env.reset(seed=seed)
    states, rewards = [obs["state"]], []
    n = 0
    while True:
        obs, reward, terminated, truncated, info = env.step(env.unwrapped.expert_action())
        states.append(obs["state"])
        rewards.append(reward)
        n += 1
        if terminated or truncated or (steps is not None and n >= steps):
            return np.array(states), obs, rewards, terminated, truncated, info


def test_gymnasiums_checker_passes():
    env = gymnasium.make(ENV, structure="pyramid", layers=1)
    check_env(env.unwrapped, skip_render_check=True)
    env.close()


def test_the_expert_builds_what_build_builds():
    """At the `fixed` level, a step per control step and the commands straight to the
    servos (no motion generator: the expert's loop open, as the build's), the expert's
    episode is the build."""
    env = gymnasium.make(
        ENV, structure="pyramid-even", layers=2, robot="panda", variation="fixed", fps=100,
        limit_commands=False,
    )  # fmt: skip
    _, obs, rewards, terminated, truncated, info = _rollout(env, seed=3)
    assert terminated and not truncated and info["is_success"] and info["failure"] is None
    assert sum(rewards) == 6 and info["bricks_placed"] == 6
    built = pyramid_sim.build("pyramid-even", layers=2, seed=3)
    assert built.success
    final = {b["index"]: b for b in info["result"]["bricks"]}
    for brick in built.bricks:
        ours = np.array(final[brick.index]["final"]["position"])
        assert np.linalg.norm(ours - np.array(brick.final.position)) < 0.0005, brick.index
    env.close()


def test_the_same_seed_gives_the_same_episode_bit_for_bit():
    env = gymnasium.make(ENV, structure="pyramid", layers=1)
    first, obs1, rewards1, *_ = _rollout(env, seed=7, steps=100)
    second, obs2, rewards2, *_ = _rollout(env, seed=7, steps=100)
    assert np.array_equal(first, second) and rewards1 == rewards2
    assert np.array_equal(obs1["bricks"], obs2["bricks"])
    other, *_ = _rollout(env, seed=8, steps=100)  # another layout: another episode
    assert np.abs(other - first).max() > 0.05
    env.close()


def test_an_unseeded_reset_gives_the_next_episode_of_the_environments_stream():
    """Gymnasium's convention: reset() continues np_random, so a trainer that never passes a
    seed sees episodes that differ, and the same ones after the same first seed."""
    env = gymnasium.make(ENV, structure="pyramid", layers=1).unwrapped
    env.reset(seed=3)
    seeds, spots = [], []
    for _ in range(3):
        _, info = env.reset()
        seeds.append(info["seed"])
        spots.append(env.plan.spawn)
    assert len(set(seeds)) == 3 and len(set(spots)) == 3
    env.reset(seed=3)
    assert [env.reset()[1]["seed"] for _ in range(3)] == seeds
    first, _ = env.reset(seed=seeds[0])  # an unseeded episode replays from its seed
    assert env.plan.spawn == spots[0]
    env.close()


def test_the_structures_place_and_the_feed_spot_vary_by_centimetres_across_seeds():
    """At `layout` (the default) each seed draws the spawn spot, its yaw, and the structure's
    shift and turn; at `fixed` every seed has DE NIRO's layout; the brick on the spot is
    observed where it was fed."""
    from pyramid_sim.learning.task.layout import brick_index

    env = gymnasium.make(ENV, structure="pyramid", layers=3).unwrapped
    spawns, centres, turns = [], [], []
    for seed in range(8):
        obs, info = env.reset(seed=seed)
        plan = env.plan
        spawns.append((plan.spawn.x, plan.spawn.y, plan.spawn.yaw))
        centres.append(np.mean([[b.target.pose.x, b.target.pose.y] for b in plan.bricks], axis=0))
        turns.append(plan.bricks[0].target.pose.yaw)
        slot = env.loop.spawner.current
        assert np.allclose(obs["bricks"][slot][:2], spawns[-1][:2], atol=1e-6)
        assert info["randomization"]["layout"]["structure_turn"] == pytest.approx(turns[-1])
    spawns, centres = np.array(spawns), np.array(centres)
    assert np.ptp(spawns[:, 0]) > 0.02 and np.ptp(spawns[:, 1]) > 0.03
    assert np.ptp(spawns[:, 2]) > np.radians(5)
    assert np.ptp(centres[:, 0]) > 0.04 and np.ptp(centres[:, 1]) > 0.04
    assert np.ptp(turns) > np.radians(15)
    fixed = gymnasium.make(ENV, structure="pyramid", layers=3, variation="fixed").unwrapped
    places = set()
    for seed in range(3):
        fixed.reset(seed=seed)
        places.add((fixed.plan.spawn, fixed.plan.bricks[0].target.pose))
    assert len(places) == 1 and fixed.plan == pyramid_sim.plan("pyramid", layers=3)
    assert brick_index(fixed.loop.handles).shape == (9, 7)
    env.close()
    fixed.close()


@pytest.mark.slow  # 120 episodes; the other tests here roll the expert out at each level once
@pytest.mark.parametrize("variation", ["fixed", "layout", "full"])
@pytest.mark.parametrize("structure", [("pyramid-even", 1), ("pyramid", 3)])
def test_the_expert_builds_at_every_level_over_twenty_seeds(variation, structure):
    """The 2-brick and the 6-brick pyramids, 20 seeds each, at the dataset's rate (the
    6-brick one through the motion generator since the twist damping:
    docs/notes/2026-11-28-learning.md)."""
    name, layers = structure
    env = gymnasium.make(ENV, structure=name, layers=layers, variation=variation)
    failed = []
    for seed in range(20):
        _, _, rewards, terminated, _, info = _rollout(env, seed=seed)
        if not (terminated and info["is_success"] and sum(rewards) == 2 * layers):
            failed.append((seed, info["failure"], info["bricks_placed"]))
    assert failed == []
    env.close()


def test_random_actions_end_an_episode_with_a_reason_never_an_error():
    env = gymnasium.make(ENV, structure="pyramid", layers=1, limit_commands=False)
    env.reset(seed=0)
    env.action_space.seed(0)
    ended = None
    for _ in range(200):
        obs, reward, terminated, truncated, info = env.step(env.action_space.sample())
        assert env.observation_space.contains(obs) and reward >= 0
        if terminated or truncated:
            ended = info
            break
    assert ended is not None  # a random arm flails: it ends naming why
    assert ended["failure"] and not ended["is_success"] and not ended["result"]["success"]
    env.close()


def test_two_environments_step_in_an_async_vector_env():
    envs = gymnasium.vector.AsyncVectorEnv(  # raw commands: random targets end an episode soon
        [lambda: gymnasium.make(ENV, structure="pyramid", layers=1, limit_commands=False)] * 2
    )
    obs, _ = envs.reset(seed=[1, 2])
    assert obs["state"].shape == (2, 16) and obs["bricks"].shape[0] == 2
    envs.action_space.seed(0)
    for _ in range(100):  # random joint targets, until one episode ends beside one going on
        obs, rewards, terminated, truncated, infos = envs.step(envs.action_space.sample())
        if terminated.any():
            break
    assert rewards.shape == (2,) and terminated.any() and not truncated.any()
    ended = int(np.flatnonzero(terminated)[0])
    assert infos["failure"][ended] and infos["result"]["success"][ended] is np.False_
    envs.close()


def test_a_bad_setting_is_refused_when_the_environment_is_made():
    with pytest.raises(pyramid_sim.ConfigError, match="brick friction"):
        gymnasium.make(ENV, structure="pyramid", layers=1, friction=-1)


def test_reset_takes_no_options_and_a_step_needs_a_live_episode():
    """Gymnasium's contract on the unwrapped environment: options it does not use are refused
    naming what it takes; a step before the first reset or after the episode ended raises
    ResetNeeded rather than simulating on."""
    env = gymnasium.make(ENV, structure="pyramid", layers=1, limit_commands=False).unwrapped
    with pytest.raises(gymnasium.error.ResetNeeded, match="before the first reset"):
        env.step(env.action_space.sample())
    for options in ({"junk": 1}, "junk"):
        with pytest.raises(pyramid_sim.ConfigError) as refused:
            env.reset(seed=0, options=options)
        assert str(refused.value).startswith(f"reset options: {options!r}; accepted None or {{}}")
    env.reset(seed=0, options={})
    env.action_space.seed(0)
    for _ in range(200):  # random targets end the episode (as above)
        _, _, terminated, truncated, info = env.step(env.action_space.sample())
        if terminated or truncated:
            break
    assert terminated and info["failure"]
    with pytest.raises(gymnasium.error.ResetNeeded, match="the episode has ended"):
        env.step(env.action_space.sample())
    env.reset(seed=0)
    env.step(env.action_space.sample())  # a new episode steps again
    env.close()


def test_rgb_array_renders_the_overview_camera():
    import os

    os.environ.setdefault("MUJOCO_GL", "egl")
    env = gymnasium.make(
        ENV, structure="pyramid", layers=1, render_mode="rgb_array", width=160, height=120
    )
    env.reset(seed=0)
    frame = env.render()
    assert frame.shape == (120, 160, 3) and frame.dtype == np.uint8 and frame.mean() > 60
    env.close()
    top = gymnasium.make(
        ENV, structure="pyramid", layers=1, render_mode="rgb_array", width=160, height=120,
        camera_name="top",
    )  # fmt: skip
    top.reset(seed=0)
    assert np.abs(top.render().astype(int) - frame.astype(int)).mean() > 10
    top.close()
    with pytest.raises(pyramid_sim.ConfigError, match="cameras: unknown 'nose'"):
        gymnasium.make(ENV, structure="pyramid", layers=1, camera_name="nose")


def test_cameras_asked_for_are_observed_at_their_size():
    import os

    os.environ.setdefault("MUJOCO_GL", "egl")
    cameras = ("overview", "left_wrist", "right_wrist")
    env = gymnasium.make(ENV, structure="pyramid", layers=1, cameras=cameras, image_size=(48, 64))
    obs, _ = env.reset(seed=0)
    assert env.observation_space.contains(obs) and tuple(obs["images"]) == cameras
    for image in obs["images"].values():
        assert image.shape == (48, 64, 3) and image.dtype == np.uint8 and image.std() > 5
    obs, *_ = env.step(env.unwrapped.expert_action())
    assert set(obs["images"]) == set(cameras)
    env.close()
    with pytest.raises(pyramid_sim.ConfigError, match="cameras: unknown 'nose'"):
        gymnasium.make(ENV, structure="pyramid", layers=1, cameras=("nose",))
    with pytest.raises(pyramid_sim.ConfigError, match="one name, not a sequence"):
        gymnasium.make(ENV, structure="pyramid", layers=1, cameras="left_wrist")
    with pytest.raises(pyramid_sim.ConfigError, match="image size: \\(0, 0\\)"):
        gymnasium.make(ENV, structure="pyramid", layers=1, image_size=(0, 0))


def test_an_expert_episode_is_kept_at_the_datasets_rate():
    """A frame each environment step (1/fps s, 4 control steps at 25 fps), each with the
    observation before its action, the reward that followed, what each arm was doing; the
    last one done and successful."""
    import os

    from pyramid_sim.learning.recording.episode import PRIMITIVES, expert_episode

    os.environ.setdefault("MUJOCO_GL", "egl")
    env = gymnasium.make(ENV, structure="pyramid", layers=1, image_size=(32, 32)).unwrapped
    frames = []
    end = expert_episode(env, seed=0, cameras=("overview", "left_wrist"), on_frame=frames.append)
    assert end.success and end.failure is None and end.frames == len(frames)
    steps = end.result["sim_time_s"] / 0.01
    assert len(frames) == pytest.approx(steps / 4, abs=1)  # the last step may end early
    assert [f.done for f in frames].count(True) == 1 and frames[-1].done
    assert [f.success for f in frames].count(True) == 1 and frames[-1].success
    # 1 brick, 3 spares, pick, goal, whether it is filled, each arm's next target, hands, holds
    assert frames[0].environment.shape == (4 * 7 + 4 + 4 + 1 + 8 + 8 + 2,)
    assert sum(f.reward for f in frames) == 1.0
    assert frames[0].state.dtype == np.float32 and frames[0].action.shape == (16,)
    assert set(frames[0].images) == {"overview", "left_wrist"}
    doing = {PRIMITIVES[p] for f in frames for p in f.primitive}
    assert {"hover", "grip", "release"} <= doing
    assert {b for f in frames for b in f.brick} == {-1, 0}
    env.close()


def test_the_time_limit_truncates_an_episode():
    env = gymnasium.make(
        ENV, structure="pyramid", layers=1, config=pyramid_sim.SimConfig(max_sim_time=1.0)
    )
    _, _, rewards, terminated, truncated, info = _rollout(env, seed=0)
    assert truncated and not terminated and not info["is_success"]
    assert 1.0 < info["sim_time_s"] <= 1.04 + 1e-9 and "within 1 s" in info["failure"]
    env.close()


def test_end_effector_actions_go_through_the_builds_own_ik():
    """action_mode="ee": each arm's tool-pose change and finger gap. The expert's moves as
    such actions still build the structure; the checker passes."""
    env = gymnasium.make(ENV, structure="pyramid", layers=1, action_mode="ee")
    assert env.action_space.shape == (10,)
    check_env(env.unwrapped, skip_render_check=True)
    _, obs, rewards, terminated, truncated, info = _rollout(env, seed=0)
    assert terminated and info["is_success"] and sum(rewards) == 1
    env.close()
    with pytest.raises(pyramid_sim.ConfigError, match="action mode: unknown 'torque'"):
        gymnasium.make(ENV, structure="pyramid", layers=1, action_mode="torque")


def _joint_targets_at_the_spot(env) -> np.ndarray:
    """Both arms' joint targets with each hand over the spawn spot at once: where the
    lockstep never lets them be together (each solved alone, the other arm away)."""
    from pyramid_sim.core.poses import Pose
    from pyramid_sim.physics.reach import ReachChecker

    checker = ReachChecker(env.loop.config)
    spot, robot = env.plan.spawn, env.loop.config.robot_description
    action = env.held_command().astype(np.float64)
    for arm in ("left", "right"):
        hover = Pose(spot.x, spot.y, spot.z + 0.15, robot.arms[arm].yaw_reference)
        q = checker.posture(arm, hover)[checker.ik.qadr[arm]]
        for k, joint in enumerate(robot.arms[arm].joints):
            action[env.layout.names.index(f"{arm}/{joint.split('/')[-1]}")] = q[k]
    return action.astype(np.float32)


def _run_until_it_ends(env, action, steps: int = 200) -> dict:
    for _ in range(steps):
        _, _, terminated, truncated, info = env.step(action)
        if terminated or truncated:
            return info
    raise AssertionError("the episode did not end")


@pytest.mark.parametrize("fault", ["contact", "speed", "torque", "off_table"])
def test_each_episode_failure_ends_a_real_episode_and_is_named(fault):
    """What ends an episode though a build would go on, each made to happen in the physics,
    never by setting a meter: both hands sent to the spawn spot at once (the arms meet), a
    wild joint target on the raw command path (the wrist whips past its speed), the left hand
    pressed down with 120 N (its wrist demands more torque than it has), a brick knocked to
    the floor. Each meter reads past its limit, and the others stay within theirs."""
    env = gymnasium.make(ENV, structure="pyramid", layers=1, limit_commands=fault != "speed")
    env = env.unwrapped
    env.reset(seed=0)
    loop = env.loop
    action = env.held_command()
    if fault == "contact":
        action = _joint_targets_at_the_spot(env)
    elif fault == "speed":
        action = action.copy()
        action[env.layout.names.index("left/panda_joint7")] += 2.0  # a step of 2 rad at once
    elif fault == "torque":
        hand = loop.model.site(loop.config.robot_description.arms["left"].tcp_site).bodyid
        loop.data.xfrc_applied[hand, 2] = -120.0
    else:
        loop.custody.feed_spot()  # a brick on the spot, then knocked to the floor
        q = loop.handles.brick_qpos[0]
        loop.data.qpos[q + 2] = -0.5
    info = _run_until_it_ends(env, action)
    monitor = loop.monitor
    words = {
        "contact": "arm-arm contact at t = ",
        "speed": "a joint moved at ",
        "torque": "a joint demanded ",
        "off_table": "slot 0) left the table",
    }
    assert info["failure"].startswith(words[fault]) or words[fault] in info["failure"]
    assert not info["is_success"]
    if fault == "contact":
        assert monitor.arm_arm_contacts > 0 and monitor.speed_ratio < 1.0
    elif fault == "speed":
        assert monitor.speed_ratio > 1.0 and monitor.arm_arm_contacts == 0
        assert f"{monitor.speed_ratio:.2f} of its velocity limit" in info["failure"]
    elif fault == "torque":
        assert monitor.torque_ratio > 1.0 and monitor.speed_ratio < 1.0
        assert f"{monitor.torque_ratio:.2f} of its torque limit" in info["failure"]
    env.close()


def test_the_control_rate_sets_dt_and_render_fps_and_the_registration_a_step_limit():
    env = gymnasium.make(ENV, structure="pyramid", layers=1, fps=50)
    assert env.unwrapped.dt == 0.02 and env.metadata["render_fps"] == 50
    assert env.unwrapped.control_steps == 2 and env.spec.max_episode_steps > 0
    env.reset(seed=0)
    env.step(env.unwrapped.expert_action())
    assert env.unwrapped.loop.data.time == pytest.approx(0.02)
    env.close()
    with pytest.raises(pyramid_sim.ConfigError, match="fps: 30; accepted 10, 20, 25, 50, 100"):
        gymnasium.make(ENV, structure="pyramid", layers=1, fps=30)


def test_reset_and_step_give_the_same_info_keys():
    env = gymnasium.make(ENV, structure="pyramid", layers=1)
    _, first = env.reset(seed=0)
    _, _, _, _, then = env.step(env.unwrapped.expert_action())
    assert set(first) == set(then) and first["result"] == {} and first["failure"] is None
    env.close()


@pytest.mark.parametrize(
    "action, words",
    [
        (np.full(16, np.nan), "not finite"),
        (np.r_[np.zeros(15), np.inf], "entries \\[15\\] are not finite"),
        (np.zeros(15), "shape \\(15,\\); accepted \\(16,\\)"),
        (0.0, "shape \\(\\); accepted \\(16,\\)"),
        (np.array(["a"] * 16), "not numeric"),
        (None, "not numeric"),
    ],
)
def test_a_bad_action_is_refused_naming_the_problem(action, words, tmp_path, monkeypatch):
    """Nothing reaches MuJoCo: no MUJOCO_LOG.TXT, and the episode goes on."""
    monkeypatch.chdir(tmp_path)
    env = gymnasium.make(ENV, structure="pyramid", layers=1).unwrapped
    env.reset(seed=0)
    with pytest.raises(ValueError, match=words):
        env.step(action)
    _, _, terminated, _, info = env.step(env.expert_action())
    assert not terminated and info["failure"] is None and list(tmp_path.iterdir()) == []
    env.close()


def test_a_policy_is_fed_bricks_whoever_drives_the_arms():
    """Without the expert: a brick lies on the spot from the first observation; once it is
    taken away (here lifted off by hand) the feeder sets the next there."""
    env = gymnasium.make(ENV, structure="pyramid-even", layers=1).unwrapped
    obs, _ = env.reset(seed=2)
    spot = env.plan.spawn
    assert np.allclose(obs["bricks"][0][:2], (spot.x, spot.y), atol=1e-6)
    hold = env.held_command()
    for _ in range(5):
        obs, *_ = env.step(hold)
    assert env.loop.spawner.next_slot == 1  # the spot holds a brick: nothing more fed
    q = env.loop.handles.brick_qpos[0]
    env.loop.data.qpos[q : q + 3] = (spot.x, spot.y + 0.45, 0.3)  # taken, and put aside
    for _ in range(10):
        obs, _, terminated, _, info = env.step(hold)
    assert env.loop.spawner.next_slot == 2 and not terminated
    assert np.allclose(obs["bricks"][1][:2], (spot.x, spot.y), atol=1e-3)
    env.close()


def test_a_jerky_command_becomes_smooth_motion_through_the_motion_generator():
    """A step of 0.3 rad on every joint at once: through the motion generator the arms get
    there smoothly and the lag it took is reported; raw, it reaches the servos and the
    episode ends on a limit."""
    smooth = gymnasium.make(ENV, structure="pyramid", layers=1).unwrapped
    smooth.reset(seed=0)
    jerk = smooth.held_command() + np.float32(0.3) * (smooth.layout.high > 1)
    for _ in range(50):
        obs, _, terminated, _, info = smooth.step(jerk)
        assert not terminated, info["failure"]
    assert 0.25 < info["command_lag"] <= 0.31  # the whole step was once ahead of the command
    joints = smooth.layout.high > 1
    assert np.allclose(obs["state"][joints], jerk[joints], atol=0.01)  # and it got there
    smooth.close()
    raw = gymnasium.make(ENV, structure="pyramid", layers=1, limit_commands=False).unwrapped
    raw.reset(seed=0)
    for _ in range(25):
        _, _, terminated, _, info = raw.step(jerk)
        if terminated:
            break
    assert terminated and "limit" in info["failure"] and info["command_lag"] == 0.0
    raw.close()


@pytest.mark.parametrize("corner", ["high", "low", "+x", "-x", "+y", "-y", "+z", "-z"])
def test_an_ee_action_inside_the_space_breaks_no_joint_limit(corner):
    """Held for 6 s at a bound of the space, both arms: the targets stay where the robot can
    follow, the joints within their speed and torque limits."""
    env = gymnasium.make(ENV, structure="pyramid", layers=1, action_mode="ee").unwrapped
    env.reset(seed=0)
    low, high = env.action_space.low, env.action_space.high
    if corner in ("high", "low"):
        action = high.copy() if corner == "high" else low.copy()
    else:
        axis = "xyz".index(corner[1])
        action = np.zeros(10, dtype=np.float32)
        action[[axis, 5 + axis]] = (high if corner[0] == "+" else low)[[axis, 5 + axis]]
    action[[4, 9]] = high[[4, 9]]
    for _ in range(150):
        _, _, terminated, truncated, info = env.step(action)
        assert not (terminated or truncated), info["failure"]
    monitor = env.loop.monitor
    monitor.flush()
    assert monitor.speed_ratio < 1.0 and monitor.torque_ratio < 1.0
    env.close()


@pytest.mark.parametrize("generator", [True, False])
def test_a_jittering_ee_policy_is_smoothed_by_the_motion_generator(generator):
    """The expert's ee actions with 2 mm of white noise on each move: through the motion
    generator (the default) the arms follow smoothly and build; straight from the IK to the
    servos the same jitter asks a joint for more torque than it has."""
    env = gymnasium.make(
        ENV, structure="pyramid-even", layers=1, variation="layout", action_mode="ee",
        limit_commands=generator,
    ).unwrapped  # fmt: skip
    env.reset(seed=0)
    noise = np.random.default_rng(0)
    while True:
        action = env.expert_action()
        for arm in (0, 5):
            action[arm : arm + 3] += noise.normal(0.0, 0.002, 3)
        _, _, terminated, truncated, info = env.step(action)
        if generator:  # the servos get the generator's command, not the IK's
            command = env.loop.data.ctrl[env.loop.handles.ctrl_index]
            np.testing.assert_allclose(command, env.generator.position, atol=1e-12)
        if terminated or truncated:
            break
    if generator:
        assert info["is_success"], info["failure"]
    else:
        assert "torque limit" in info["failure"]


def test_a_reset_that_changes_no_physical_part_keeps_the_compiled_scene():
    env = gymnasium.make(ENV, structure="pyramid", layers=1).unwrapped
    env.reset(seed=0)
    model = env.loop.model
    env.reset(seed=1)  # another layout: the spawn marker moved in the same model
    assert env.loop.model is model
    assert np.allclose(model.site("spawn_marker").pos[:2], (env.plan.spawn.x, env.plan.spawn.y))
    full = gymnasium.make(ENV, structure="pyramid", layers=1, variation="full").unwrapped
    full.reset(seed=0)
    first = full.loop.model
    full.reset(seed=1)
    assert full.loop.model is not first  # another brick, another compiled scene
    env.close()
    full.close()


def test_the_expert_picks_the_brick_where_an_imprecise_feeder_set_it():
    """With spawn jitter the brick lies millimetres off the spot: each pick's moves are aimed
    at the brick as it lies, not at the nominal spot."""
    env = gymnasium.make(
        ENV, structure="pyramid-even", layers=1, variation="fixed", spawn_jitter_mm=8.0
    ).unwrapped
    env.reset(seed=5)
    loop, spot = env.loop, env.plan.spawn
    aimed = {}
    while len(aimed) < 2:
        env.step(env.expert_action())
        for arm in ("left", "right"):
            step = loop.step_of(arm)
            if step is not None and step.name == "servo" and arm not in aimed:
                slot = loop.spawner.offered
                brick = loop.spawner.lies_at(loop.data, slot)
                aimed[arm] = (step.pose, brick)
    for arm, (pose, brick) in aimed.items():
        assert np.hypot(brick.x - spot.x, brick.y - spot.y) > 0.001, arm  # the feeder missed
        assert abs(pose.x - brick.x) < 1e-4 and abs(pose.y - brick.y) < 1e-4, arm
    env.close()


def test_a_layout_that_stands_the_structure_by_the_spot_is_refused():
    """The feeder sets no brick beside one that near: such a layout is refused (a drawn one
    is drawn again)."""
    from pyramid_sim.config import LayoutConfig
    from pyramid_sim.learning.task.episodes import check_spot_clear

    near = pyramid_sim.SimConfig(layout=LayoutConfig(structure_shift=(-0.1, 0.0)))
    plan = pyramid_sim.plan("pyramid", layers=3, config=near)
    with pytest.raises(pyramid_sim.ConfigError, match="from the spawn spot's brick; accepted 60"):
        check_spot_clear(plan, near)
    check_spot_clear(pyramid_sim.plan("pyramid", layers=3), pyramid_sim.SimConfig())


def test_a_layout_the_expert_cannot_build_is_drawn_again_from_the_seed():
    """Seed 100001's first draw stands the 6-brick pyramid by the spot (the feeder stalled
    there): the episode takes the seed's next draw, and says so."""
    from pyramid_sim.learning.task import variation as var

    env = gymnasium.make(ENV, structure="pyramid", layers=3).unwrapped
    _, info = env.reset(seed=100001)
    attempt = info["randomization"]["layout"]["attempt"]
    assert attempt >= 1
    first = var.placed(env.config, var.draw_layout(100001, "layout", 0))
    with pytest.raises(pyramid_sim.ConfigError, match="from the spawn spot's brick"):
        env.episodes.plan(first)
    again = var.draw_layout(100001, "layout", attempt)
    assert again == info["randomization"]["layout"]
    env.close()


def test_a_target_whose_brick_is_knocked_out_of_the_tolerances_is_held_no_more():
    """Success is every target held at once: a brick found in place and then knocked 8 mm
    away takes its target's reward back and leaves the observation's `placed` flag."""
    env = gymnasium.make(
        pyramid_sim.ENV_ID,
        structure="pyramid-even",
        layers=1,
        variation="layout",
        action_mode="anchored",
    ).unwrapped
    env.reset(seed=100_000)
    while env.placing.count == 0:
        observation, reward, terminated, truncated, info = env.step(env.expert_action())
        assert not (terminated or truncated)
    goal = next(iter(env.placing.placed))
    q = env.loop.handles.brick_qpos[env.placing.placed[goal]]
    env.loop.data.qpos[q] += 0.008
    assert info["bricks_placed"] == 1
    observation, reward, _, _, info = env.step(env.expert_action())
    assert reward == -1.0
    assert env.placing.count == 0 and info["bricks_placed"] == 0
    assert observation["placed"][goal] == 0.0
    env.close()
