"""Each robot preset loads clean, matches its description, and builds; Baxter builds DE NIRO's
even pyramid in its own frame."""

import math

import mujoco
import numpy as np
import pytest

import pyramid_sim
from pyramid_sim.config import SimConfig
from pyramid_sim.core.primitives import clear_pose
from pyramid_sim.physics import names as c
from pyramid_sim.physics.handles import SceneHandles
from pyramid_sim.physics.ik import DualArmIK
from pyramid_sim.physics.scene import build_scene
from pyramid_sim.robots import PRESETS

ROBOTS = sorted(PRESETS)


def _robot_contacts(model: mujoco.MjModel, data: mujoco.MjData) -> list[tuple[str, str]]:
    """Contacts that involve no brick (the magazine rests on the floor)."""
    pairs = []
    for i in range(data.ncon):
        con = data.contact[i]
        names = [model.body(model.geom_bodyid[g]).name for g in (con.geom1, con.geom2)]
        if not any(n.startswith(c.BRICK_PREFIX) for n in names):
            pairs.append(tuple(names))
    return pairs


def _scene(name: str, bricks: int):
    """A preset's compiled scene, fresh data and handles."""
    config = SimConfig.for_robot(name)  # the robot at its own scale
    model = build_scene(config, bricks).model
    return (
        config,
        config.robot_description,
        model,
        mujoco.MjData(model),
        SceneHandles(model, config.robot_description, bricks),
    )


@pytest.mark.parametrize("name", ROBOTS)
def test_a_preset_has_no_self_contact_at_home_or_at_its_clear_poses(name):
    config, robot, model, data, handles = _scene(name, 2)
    ik = DualArmIK(config, limit_acceleration=False)
    clear = {a: ik.solve(a, clear_pose(a, robot)) for a in c.ARMS}
    for pose in ({a: robot.arms[a].home for a in c.ARMS}, clear):
        for arm in c.ARMS:
            data.qpos[handles.arm_qpos[arm]] = pose[arm]
        mujoco.mj_forward(model, data)
        assert _robot_contacts(model, data) == []


@pytest.mark.parametrize("name", ROBOTS)
def test_the_pads_close_to_the_width_the_preset_says(name):
    """The model's own geometry, fingers closed and fully open, against the description."""
    _, robot, model, data, handles = _scene(name, 1)
    arm = robot.arms["left"]
    widths = []
    for travel in (0.0, robot.finger_stroke):
        fingers = handles.finger_qpos["left"]
        for q, gain in zip(fingers, robot.finger_gains):
            data.qpos[q] = 2 * travel / (len(fingers) * gain)  # the gap opened 2 x travel
        mujoco.mj_forward(model, data)
        pads = [model.geom(p).id for p in arm.pads]
        gap = np.zeros(6)
        widths.append(mujoco.mj_geomDistance(model, data, pads[0], pads[1], 1.0, gap))
    assert widths[0] == pytest.approx(robot.closed_width, abs=2e-4)
    assert widths[1] == pytest.approx(robot.closed_width + 2 * robot.finger_stroke, abs=2e-4)
    assert widths[1] > SimConfig.for_robot(name).brick.width > widths[0]


@pytest.mark.parametrize("name", ROBOTS)
def test_a_noisy_second_raises_no_warning(name):
    _, robot, model, data, handles = _scene(name, 4)
    data.ctrl[:] = 0.0
    for arm in c.ARMS:
        data.qpos[handles.arm_qpos[arm]] = robot.arms[arm].home
        data.ctrl[handles.arm_actuators[arm]] = robot.arms[arm].home
    mujoco.mj_forward(model, data)
    rng = np.random.default_rng(0)
    low, high = model.actuator_ctrlrange.T
    for _ in range(int(1.0 / model.opt.timestep)):
        data.ctrl[:] = np.clip(data.ctrl + rng.normal(0, 0.01, model.nu), low, high)
        mujoco.mj_step(model, data)
    assert all(w.number == 0 for w in data.warning)
    assert np.all(np.isfinite(data.qpos))


def test_baxter_reaches_the_seeds_even_pyramid_of_four_layers_not_five():
    from pyramid_sim.physics.reach import ReachChecker

    checker = ReachChecker(SimConfig(robot="baxter"))
    assert checker.largest(pyramid_sim.structure("pyramid-even"), "both") == 4


def test_baxter_builds_the_even_pyramid_of_two_layers():
    result = pyramid_sim.build("pyramid-even", layers=2, robot="baxter")
    assert result.success, result.failure_reason
    assert result.robot == "baxter" and result.bricks_placed == 6
    for b in result.bricks:
        x, y, z = b.final.position
        tx, ty, tz = b.target.position
        assert math.hypot(x - tx, y - ty) < 0.005 and abs(z - tz) < 0.003, b
    assert result.arm_arm_contacts == 0 and result.arm_body_contacts == 0
    assert result.max_joint_torque_ratio <= 1.0 and result.drops == 0


def test_an_arm_against_its_own_robot_is_counted():
    """Baxter's left arm folded into its head padding: the monitor counts contacts with the
    robot's body (a check of success), and none between the arms."""
    from pyramid_sim.physics.monitor import StepMonitor, joint_limits

    _, robot, model, data, handles = _scene("baxter", 1)
    data.qpos[handles.arm_qpos["left"]] = [-0.31, -0.39, -2.89, 1.96, 0.23, -0.36, 1.76]
    data.qpos[handles.arm_qpos["right"]] = robot.arms["right"].home
    mujoco.mj_forward(model, data)
    arms = lambda part: np.concatenate([part[a] for a in c.ARMS])  # noqa: E731
    monitor = StepMonitor(
        model,
        data,
        arms(handles.arm_dofs),
        arms(handles.arm_qpos),
        arms(handles.arm_actuators),
        arms(handles.finger_qpos),
        joint_limits(model, robot),
    )
    monitor.record()
    monitor.flush()
    assert monitor.arm_body_contacts > 0 and monitor.arm_arm_contacts == 0
