"""Compose the MuJoCo scene: assets/ world, two Pandas from example-robot-data, a brick magazine.

The Panda comes from example-robot-data's URDF (collision meshes serve as visuals: the visual
meshes are .dae, which MuJoCo cannot read). What is changed from the URDF, and why:
- each finger mounted `GripperConfig.spacer` further out (the brick is 86 mm wide, the stock
  gripper opens 80 mm), the finger joints keeping the real hand's 0-40 mm;
- one force-limited position actuator on a tendon coupling both fingers (command = finger gap),
  the fingers kept symmetric by a joint equality;
- position actuators on the arm joints with the real arm's torque limits, armature 0.1,
  damping (JOINT_DAMPING) and gravity compensation that counts against those limits
  (actuatorgravcomp: the URDF brings no actuators and almost no damping);
- the rubber finger tips ("pads") get their own friction, stiff contact and a higher priority so a
  held brick does not creep, while the brick's friction is that of brick-brick and brick-table
  contacts: the table top takes the brick's friction, as MuJoCo mixes two geoms' by the larger.
"""

from __future__ import annotations

import importlib.metadata
import math
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import mujoco
import numpy as np

from ..config import SimConfig
from ..resources import ASSETS
from . import names as c

PAD_SOLREF = (0.004, 1.0)
PAD_SOLIMP = (0.99, 0.999, 0.0005, 0.5, 2.0)
PARK_Z = -0.671 + 0.031  # bricks waiting in the magazine lie on the floor behind the robots
# Long axis along x: rows a brick length and 0.108 m apart, columns a width and 0.114 m (rows
# closer than a brick's length interpenetrate, and MuJoCo throws the bricks across the floor).
PARK_ROW_PITCH, PARK_COLUMN_PITCH = 0.30, 0.20


@lru_cache(maxsize=1)
def panda_urdf_dir() -> Path:
    """Folder of example-robot-data's Panda description (its Python module needs pinocchio)."""
    dist = importlib.metadata.distribution("example-robot-data")
    root = Path(str(dist.locate_file("cmeel.prefix/share/example-robot-data/robots")))
    return root / "panda_description"


def panda_spec(config: SimConfig) -> mujoco.MjSpec:
    """One Panda with the changes listed in this module's docstring."""
    root = panda_urdf_dir()
    text = (root / "urdf" / "panda.urdf").read_text()
    meshes = root / "meshes" / "collision"
    # Absolute mesh paths survive attach() and to_xml(); the .dae visuals are discarded.
    text = text.replace(
        "package://example-robot-data/robots/panda_description/meshes/collision/", f"{meshes}/"
    )
    compiler = '<mujoco><compiler fusestatic="false" discardvisual="true"/></mujoco>'
    robot_tag_end = text.index(">", text.index("<robot")) + 1
    text = text[:robot_tag_end] + compiler + text[robot_tag_end:]
    spec = mujoco.MjSpec.from_string(text)
    _tune_arm(spec)
    _add_gripper(spec, config)
    spec.body("panda_hand_tcp").add_site(name=c.TCP_SITE, size=[0.005, 0, 0], rgba=[0, 1, 0, 0])
    return spec


def _tune_arm(spec: mujoco.MjSpec) -> None:
    for name, kp, damping, torque in zip(
        c.ARM_JOINTS, c.JOINT_KP, c.JOINT_DAMPING, c.JOINT_TORQUE_LIMITS
    ):
        joint = spec.joint(name)
        joint.armature = 0.1
        joint.damping = [damping, 0.0, 0.0]
        act = spec.add_actuator(name=name, target=name, trntype=mujoco.mjtTrn.mjTRN_JOINT)
        act.set_to_position(kp=kp, kv=0.0)
        act.ctrlrange = joint.range
        act.ctrllimited = True
        act.forcerange = [-torque, torque]
        act.forcelimited = True
        # Gravity compensation is the servo's work, not a free torque: it counts against the
        # joint's limit together with the servo's output.
        joint.actgravcomp = True
        joint.actfrcrange = [-torque, torque]
        joint.actfrclimited = True
    for body in spec.bodies:
        if body.name.startswith("panda_") and body.name != "panda_link0":
            body.gravcomp = 1.0


def _add_gripper(spec: mujoco.MjSpec, config: SimConfig) -> None:
    grip = config.gripper
    for joint_name in c.FINGER_JOINTS:
        joint = spec.joint(joint_name)
        joint.range = [0.0, grip.stroke]  # the URDF's own 0-40 mm unless a smaller one is asked
        joint.damping = [2.0, 0.0, 0.0]
        joint.armature = 0.01
    # The spacers: each finger mounted further out along its own sliding axis.
    for body_name, joint_name in zip(c.FINGER_BODIES, c.FINGER_JOINTS):
        body, axis = spec.body(body_name), np.array(spec.joint(joint_name).axis)
        body.pos = np.array(body.pos) + grip.spacer * axis
    for body_name, pad_name in zip(c.FINGER_BODIES, c.PAD_GEOMS):
        pad = spec.body(body_name).geoms[3]  # the URDF's "rubber tip with which to grasp"
        pad.name = pad_name
        pad.friction = [grip.pad_friction, 0.02, 0.0002]
        pad.condim = 4
        pad.priority = 1
        pad.solref = list(PAD_SOLREF)
        pad.solimp = list(PAD_SOLIMP)
        pad.rgba = [0.15, 0.15, 0.15, 1]
    tendon = spec.add_tendon(name=c.GRIPPER_TENDON)
    for joint_name in c.FINGER_JOINTS:
        tendon.wrap_joint(joint_name, 1.0)
    # The URDF's <mimic> arrives as a joint equality; stiffen it so the fingers stay symmetric.
    for eq in spec.equalities:
        if eq.type == mujoco.mjtEq.mjEQ_JOINT:
            eq.solref = [0.005, 1.0]
    act = spec.add_actuator(
        name=c.GRIPPER_ACTUATOR, target=c.GRIPPER_TENDON, trntype=mujoco.mjtTrn.mjTRN_TENDON
    )
    # Stiff enough that any gap command short of the brick saturates at the force limit.
    act.set_to_position(kp=grip.stiffness, kv=40.0)
    act.ctrlrange = [0.0, 2 * grip.stroke]
    act.ctrllimited = True
    act.forcerange = [-grip.force, grip.force]
    act.forcelimited = True


def brick_spec(config: SimConfig) -> mujoco.MjSpec:
    """The brick of assets/brick.xml sized, weighed and with the friction of this run."""
    spec = mujoco.MjSpec.from_file(str(ASSETS / "brick.xml"))
    brick = config.brick
    geom = spec.geom("geom")
    geom.size = [brick.length / 2, brick.width / 2, brick.height / 2]
    geom.mass = brick.mass
    geom.friction = [brick.friction, 0.005, 0.0001]
    return spec


def park_position(slot: int) -> np.ndarray:
    """Where magazine brick `slot` waits: a grid on the floor behind the robots."""
    row, col = divmod(slot, 8)
    return np.array([-0.55 - PARK_ROW_PITCH * row, -0.7 + PARK_COLUMN_PITCH * col, PARK_Z])


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
    spawn = spec.site("spawn_marker")
    spawn.pos = [layout.spawn_xy[0], layout.spawn_xy[1], layout.table_top_z + 0.0005]
    spawn.quat = _yaw_quat(layout.spawn_yaw)
    # Where the next brick will be set: no contact, nothing drawn; the spawner measures how
    # near bricks and arm links are to it.
    jitter = layout.spawn_jitter_mm / 1000.0
    brick = config.brick
    spec.worldbody.add_geom(
        name=c.SPAWN_VOLUME, type=mujoco.mjtGeom.mjGEOM_BOX, contype=0, conaffinity=0, group=5,
        size=[brick.length / 2 + jitter, brick.width / 2 + jitter, brick.height / 2],
        pos=[layout.spawn_xy[0], layout.spawn_xy[1], layout.table_top_z + brick.height / 2],
        quat=_yaw_quat(layout.spawn_yaw), rgba=[0, 0, 0, 0], mass=0,
    )
    for arm, base in zip(c.ARMS, (layout.left_base, layout.right_base)):
        frame = spec.worldbody.add_frame(pos=list(base))
        spec.attach(panda_spec(config), prefix=f"{arm}/", frame=frame)
    if with_bricks:
        # MuJoCo counts the contacts between the two arms' subtrees in C, every step.
        spec.add_sensor(
            name=c.ARM_ARM_SENSOR, type=mujoco.mjtSensor.mjSENS_CONTACT,
            objtype=mujoco.mjtObj.mjOBJ_XBODY, objname=c.prefixed("left", c.ARM_ROOT_BODY),
            reftype=mujoco.mjtObj.mjOBJ_XBODY, refname=c.prefixed("right", c.ARM_ROOT_BODY),
            intprm=[1, 3, 1],  # data "found", reduce "netforce": one value, the contact count
        )
        for slot in range(n_bricks):
            frame = spec.worldbody.add_frame(pos=list(park_position(slot)))
            spec.attach(brick_spec(config), prefix=c.brick_name(slot), frame=frame)
    return spec


def build_scene(config: SimConfig, n_bricks: int) -> Scene:
    """Compile the full scene with a magazine of `n_bricks` bricks."""
    model = build_spec(config, n_bricks).compile()
    return Scene(model=model, n_bricks=n_bricks)


def _yaw_quat(yaw: float) -> list[float]:
    return [math.cos(yaw / 2), 0.0, 0.0, math.sin(yaw / 2)]


def write_scene(config: SimConfig, n_bricks: int, path: Path) -> mujoco.MjModel:
    """The compiled scene of a build, written atomically: `.mjb` (MuJoCo's binary model,
    self-contained) or `.xml` (MJCF, mesh paths absolute). Returns the model."""
    from ..output.files import write_atomic

    spec = build_spec(config, n_bricks)
    model = spec.compile()
    if path.suffix.lower() == ".mjb":
        write_atomic(path, lambda tmp: mujoco.mj_saveModel(model, str(tmp), None))
    else:
        xml = spec.to_xml()
        write_atomic(path, lambda tmp: tmp.write_text(xml))
    return model
