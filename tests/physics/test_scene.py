"""The scene compiles with its table, bricks, robot and sensors (its stability under noisy commands is tested
for every robot preset in test_robots.py)."""

import mujoco
import numpy as np
import pytest

from pyramid_sim.config import BrickConfig, SimConfig
from pyramid_sim.physics import names as c
from pyramid_sim.physics.handles import SceneHandles
from pyramid_sim.physics.scene import build_scene
from pyramid_sim.robots.panda import PANDA

pytestmark = pytest.mark.physics


def test_scene_holds_two_pandas_a_table_and_the_magazine():
    model = build_scene(SimConfig(), 5).model
    for arm in c.ARMS:
        for joint, torque in zip(PANDA.arms[arm].joints, PANDA.arms[arm].torque_limits):
            assert model.actuator(joint).forcerange[1] == torque
        finger = model.joint(PANDA.arms[arm].finger_joints[0])
        assert finger.range[1] == 0.04  # the real hand's: the brick is spanned with spacers
    table = model.geom(c.TABLE_GEOM)  # the table top the bricks rest on: a colliding box
    assert table.type[0] == mujoco.mjtGeom.mjGEOM_BOX and table.contype[0] and table.conaffinity[0]
    assert sum(model.body(i).name.endswith("/brick") for i in range(model.nbody)) == 5


def test_brick_mass_and_friction_are_settable():
    config = SimConfig(brick=BrickConfig(mass=0.8, friction=0.6))
    model = build_scene(config, 1).model
    geom = model.geom(c.brick_name(0) + "geom")
    assert model.body(c.brick_name(0) + "brick").mass[0] == np.float64(0.8)
    assert geom.friction[0] == 0.6
    assert geom.size.tolist() == [0.096, 0.043, 0.031]


def _arm_pose(model: mujoco.MjModel, data: mujoco.MjData, arm: str, q: list[float]) -> None:
    data.qpos[SceneHandles(model, PANDA, 1).arm_qpos[arm]] = q


def test_arm_arm_contact_sensor_counts_only_contacts_between_the_arms():
    model = build_scene(SimConfig(), 1).model
    data = mujoco.MjData(model)
    adr = model.sensor(c.ARM_ARM_SENSOR).adr[0]
    SceneHandles(model, PANDA, 1).place_brick(data, 0, [0.6, 0.0, 0.109])  # 1 mm into the table
    reach = [1.2, 0.0, -0.6, 0.0, 1.9, 0.785]
    for yaw in (0.0, 1.57):  # forward, then each arm turned towards the other
        _arm_pose(model, data, "left", [-yaw, *reach])
        _arm_pose(model, data, "right", [yaw, *reach])
        mujoco.mj_forward(model, data)
        if yaw == 0.0:
            assert data.ncon > 0 and data.sensordata[adr] == 0  # contacts, none arm-arm
        else:
            assert data.sensordata[adr] > 0


def test_resting_bricks_sleep_and_a_moved_brick_wakes():
    model = build_scene(SimConfig(), 2).model
    data = mujoco.MjData(model)
    for _ in range(500):
        mujoco.mj_step(model, data)
    trees = [model.body_treeid[model.body(c.brick_name(i) + "brick").id] for i in range(2)]
    assert all(data.tree_asleep[t] >= 0 for t in trees)
    handles = SceneHandles(model, PANDA, 2)
    handles.place_brick(data, 0, [0.49, 0.01, 0.2])  # as the spawner does: 9 cm above the table
    q = handles.brick_qpos[0]
    for _ in range(200):
        mujoco.mj_step(model, data)
    assert abs(data.qpos[q + 2] - 0.11) < 1e-3  # it fell onto the table
    assert data.tree_asleep[trees[1]] >= 0  # the other stayed asleep


@pytest.mark.parametrize("top", [0.079, 0.12])
def test_the_table_stands_where_the_settings_put_its_top(top):
    """table_top_z moves the table itself (its base still reaching the floor), not only the
    spawn spot and the targets; a value out of range, NaN included, is refused."""
    from pyramid_sim.config import LayoutConfig
    from pyramid_sim.errors import ConfigError

    config = SimConfig(layout=LayoutConfig(table_top_z=top))
    model = build_scene(config, 1).model
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    table, base = model.geom("table_top").id, model.geom("table_leg").id
    assert data.geom_xpos[table][2] + model.geom_size[table][2] == pytest.approx(top, abs=1e-12)
    assert data.geom_xpos[base][2] - model.geom_size[base][2] == pytest.approx(-0.671, abs=1e-12)
    assert data.site_xpos[model.site("spawn_marker").id][2] == pytest.approx(top + 0.0005)
    for bad in (float("nan"), -0.1, 0.5):
        with pytest.raises(ConfigError, match="table top z"):
            LayoutConfig(table_top_z=bad)


def test_the_floor_holds_a_brick_beyond_where_it_is_drawn():
    """The floor is drawn 8 m square (an infinite plane's grid is slow to draw on the CPU), but
    it collides as an infinite plane: a brick dropped 20 m out comes to rest on it."""
    model = build_scene(SimConfig(), 1).model
    floor = model.geom("floor").id
    assert model.geom_size[floor][0] == 4.0  # drawn to 4 m from the centre
    data = mujoco.MjData(model)
    body = model.body(c.brick_name(0) + "brick")
    adr = model.jnt_qposadr[body.jntadr[0]]
    data.qpos[adr : adr + 7] = [20.0, 3.0, -0.5, 1, 0, 0, 0]
    for _ in range(2000):
        mujoco.mj_step(model, data)
    half_height = model.geom(model.body_geomadr[body.id]).size[2]
    assert data.qpos[adr + 2] == pytest.approx(-0.671 + half_height, abs=1e-3)
