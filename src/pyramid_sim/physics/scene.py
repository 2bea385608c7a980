"""Compose the MuJoCo scene: assets/ world (floor, table, lights, cameras), the preset's robot
(physics/robot_models/), a magazine of bricks, and the sensors that count unwanted contacts.

The bricks' friction is that of brick-brick and brick-table contacts: the table top takes the
bricks' friction, as MuJoCo gives a contact the larger of its two geoms'.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import mujoco
import numpy as np

from ..config import LayoutConfig, SimConfig
from ..core.poses import yaw_quaternion
from ..resources import ASSETS
from ..robots import RobotDescription
from . import names as c
from .robot_models import add_robot

FLOOR_Z = -0.671  # m: the floor of scene.xml, below the robots' pedestals
# Long axis along x: rows a brick length and 0.108 m apart, columns a width and 0.114 m (rows
# closer than a brick's length interpenetrate, and MuJoCo throws the bricks across the floor).
PARK_ROW_PITCH, PARK_COLUMN_PITCH = 0.30, 0.20
MARKER_MARGIN = 0.006  # m the spawn marker shows around the brick
PARK_X = -1.3  # m, the first row: behind the back wall (x = -1.0), out of every camera's sight


def brick_spec(config: SimConfig) -> mujoco.MjSpec:
    """The brick of assets/brick.xml sized, weighed and with the friction of this run."""
    spec = mujoco.MjSpec.from_file(str(ASSETS / "brick.xml"))
    brick = config.brick
    geom = spec.geom("geom")
    geom.size = [brick.length / 2, brick.width / 2, brick.height / 2]
    geom.mass = brick.mass
    geom.friction = [brick.friction, 0.005, 0.0001]
    # by its absolute path, as a portable scene's XML needs (output/scene_files.py)
    spec.texture("surface").file = str(ASSETS / "brick_surface.png")
    return spec


def park_position(slot: int, height: float) -> np.ndarray:
    """Where magazine brick `slot` (`height` tall) waits: lying on the floor behind the back
    wall, in a grid."""
    row, col = divmod(slot, 8)
    z = FLOOR_Z + height / 2
    return np.array([PARK_X - PARK_ROW_PITCH * row, -0.7 + PARK_COLUMN_PITCH * col, z])


@dataclass(frozen=True)
class Scene:
    """A compiled scene and the number of bricks in its magazine."""

    model: mujoco.MjModel
    n_bricks: int


def build_spec(config: SimConfig, n_bricks: int, *, with_bricks: bool = True) -> mujoco.MjSpec:
    """The full scene as an MjSpec (without bricks: the arms-only model used for IK)."""
    spec = mujoco.MjSpec.from_file(str(ASSETS / "scene.xml"))
    spec.option.timestep = config.timestep
    layout = config.layout
    # MuJoCo takes the larger of two geoms' frictions: the table top takes the bricks', so the
    # swept friction is the friction of brick-table contacts too.
    spec.geom(c.TABLE_GEOM).friction = [config.brick.friction, 0.005, 0.0001]
    _place_table(spec, layout.table_top_z)
    spawn = spec.site("spawn_marker")  # the brick's footprint, a little larger, as it lies
    spawn.pos = [layout.spawn_xy[0], layout.spawn_xy[1], layout.table_top_z + 0.0005]
    spawn.quat = list(yaw_quaternion(layout.spawn_yaw))
    spawn.size = [
        config.brick.length / 2 + MARKER_MARGIN,
        config.brick.width / 2 + MARKER_MARGIN,
        0.0005,
    ]
    # Where the next brick will be set: no contact, nothing drawn; the spawner measures how
    # near bricks and arm links are to it.
    jitter = layout.spawn_jitter_mm / 1000.0
    brick = config.brick
    spec.worldbody.add_geom(
        name=c.SPAWN_VOLUME,
        type=mujoco.mjtGeom.mjGEOM_BOX,
        contype=0,
        conaffinity=0,
        group=5,
        size=[brick.length / 2 + jitter, brick.width / 2 + jitter, brick.height / 2],
        pos=[layout.spawn_xy[0], layout.spawn_xy[1], layout.table_top_z + brick.height / 2],
        quat=list(yaw_quaternion(layout.spawn_yaw)),
        rgba=[0, 0, 0, 0],
        mass=0,
    )
    robot = add_robot(spec, config)
    if with_bricks:
        _add_contact_sensors(spec, robot)
        for slot in range(n_bricks):
            frame = spec.worldbody.add_frame(pos=list(park_position(slot, config.brick.height)))
            spec.attach(brick_spec(config), prefix=c.brick_name(slot), frame=frame)
    return spec


def _place_table(spec: mujoco.MjSpec, top_z: float) -> None:
    """The table with its top at `top_z` (the settings' table_top_z), its base reaching down
    to the floor."""
    top = spec.geom(c.TABLE_GEOM)
    half = top.size[2]
    table = spec.body("table")
    table.pos = [table.pos[0], table.pos[1], top_z - half]
    base = spec.geom("table_leg")
    bottom = top_z - 2 * half  # the underside of the top
    base.size = [base.size[0], base.size[1], (bottom - FLOOR_Z) / 2]
    base.pos = [0.0, 0.0, (bottom + FLOOR_Z) / 2 - (top_z - half)]


def place_spawn(model: mujoco.MjModel, config: SimConfig) -> None:
    """The spawn marker and volume where `config`'s layout puts them, written into a compiled
    scene as `build_spec` places them: a scene compiled once serves every layout."""
    layout, brick = config.layout, config.brick
    x, y = layout.spawn_xy
    turn = yaw_quaternion(layout.spawn_yaw)
    site = model.site("spawn_marker").id
    model.site_pos[site] = [x, y, layout.table_top_z + 0.0005]
    model.site_quat[site] = turn
    volume = model.geom(c.SPAWN_VOLUME).id
    model.geom_pos[volume] = [x, y, layout.table_top_z + brick.height / 2]
    model.geom_quat[volume] = turn


def scene_key(config: SimConfig) -> SimConfig:
    """What a compiled scene is made from: the settings less the spawn spot's place (which
    `place_spawn` moves), the structure's place and the random seed (which it does not hold)."""
    layout = replace(
        config.layout,
        spawn_xy=LayoutConfig.spawn_xy,
        spawn_yaw=LayoutConfig.spawn_yaw,
        structure_shift=LayoutConfig.structure_shift,
        structure_turn=LayoutConfig.structure_turn,
    )
    return replace(config, layout=layout, seed=0)


def build_scene(config: SimConfig, n_bricks: int) -> Scene:
    """Compile the full scene with a magazine of `n_bricks` bricks."""
    model = build_spec(config, n_bricks).compile()
    return Scene(model=model, n_bricks=n_bricks)


def _add_contact_sensors(spec: mujoco.MjSpec, robot: RobotDescription) -> None:
    """MuJoCo counts, in C every step, the contacts between the two arms' subtrees, and between
    each arm and each body of the robot's own (torso, head)."""
    count = [1, 3, 1]  # data "found", reduce "netforce": one value, the contact count
    arms = robot.arms
    spec.add_sensor(
        name=c.ARM_ARM_SENSOR,
        type=mujoco.mjtSensor.mjSENS_CONTACT,
        objtype=mujoco.mjtObj.mjOBJ_XBODY,
        objname=arms["left"].root_body,
        reftype=mujoco.mjtObj.mjOBJ_XBODY,
        refname=arms["right"].root_body,
        intprm=count,
    )
    for arm in c.ARMS:
        for i, body in enumerate(robot.static_bodies):
            spec.add_sensor(
                name=f"{c.ARM_BODY_SENSOR}{arm}_{i}",
                type=mujoco.mjtSensor.mjSENS_CONTACT,
                objtype=mujoco.mjtObj.mjOBJ_XBODY,
                objname=arms[arm].root_body,
                reftype=mujoco.mjtObj.mjOBJ_BODY,
                refname=body,
                intprm=count,
            )
