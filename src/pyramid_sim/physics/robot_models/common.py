"""What every robot's model gets, whatever its source: position servos with the real limits
(gravity compensation counted against them), one force-limited gripper servo on a tendon across
both fingers, and finger pads with their own friction and stiff contact."""

from __future__ import annotations

import importlib.metadata
from functools import lru_cache
from pathlib import Path

import mujoco
import numpy as np

from ...config import GripperConfig
from ...robots import ArmDescription, RobotDescription

PAD_SOLREF = (0.004, 1.0)
PAD_SOLIMP = (0.99, 0.999, 0.0005, 0.5, 2.0)
GRIPPER_DAMPING = 40.0  # N s/m of the gripper servo


def tune_finger(joint: mujoco.MjsJoint) -> None:
    """A finger joint's damping and armature, the same on every hand."""
    joint.damping = [2.0, 0.0, 0.0]
    joint.armature = 0.01


# MuJoCo's renderer draws geom groups 0-2 by default: the robots' visual meshes go in 2, their
# collision geometry in 3, so the camera shows the robot as it looks and the physics uses the
# shapes it touches with.
VISUAL_GROUP, COLLISION_GROUP = 2, 3


def hide_collision_geoms(spec: mujoco.MjSpec) -> None:
    """Every colliding geom of `spec` (a robot's own spec) out of the camera's sight."""
    for geom in spec.geoms:
        if geom.contype or geom.conaffinity:
            geom.group = COLLISION_GROUP


@lru_cache(maxsize=1)
def robots_dir() -> Path:
    """example-robot-data's robots folder (its Python module needs pinocchio: not used)."""
    dist = importlib.metadata.distribution("example-robot-data")
    return Path(str(dist.locate_file("cmeel.prefix/share/example-robot-data/robots")))


# The wrist camera, in the tool frame (z out of the hand, fingers closing along y, a held
# brick's long axis along x): off to the side the fingers do not close along, 0.14 m out (past
# the held brick's end, 0.096 m) and 0.10 m back from the tool centre, at the level of the
# hand's underside, so the hand hides no more than the fingers' roots; it looks at a point
# 2 cm ahead of the tool centre. Both fingers and their tips are in view, one either side of
# the image's middle, with the brick between them from approach to release, and the table or
# the structure beyond. Image right is the tool's +y, image up points ahead, away from the
# hand (the hand's underside along the bottom edge).
WRIST_CAMERA_AT = (0.14, 0.0, -0.10)  # m
WRIST_CAMERA_LOOKS_AT = (0.0, 0.0, 0.02)  # m
WRIST_CAMERA_FOVY = 65.0  # degrees


def add_tool(body: mujoco.MjsBody, arm: ArmDescription) -> None:
    """The arm's tool centre point (a site) and its wrist camera on the hand's `body`, whose
    frame is the tool frame."""
    body.add_site(name=local(arm.tcp_site), size=[0.005, 0, 0], rgba=[0, 1, 0, 0])
    at, target = np.array(WRIST_CAMERA_AT), np.array(WRIST_CAMERA_LOOKS_AT)
    back = (at - target) / np.linalg.norm(at - target)  # a camera looks along its -z
    right = np.array([0.0, 1.0, 0.0])  # the fingers close across the image
    up = np.cross(back, right)
    body.add_camera(
        name=local(arm.wrist_camera), pos=list(at), xyaxes=[*right, *up], fovy=WRIST_CAMERA_FOVY
    )


def local(name: str) -> str:
    """A name as the robot's own model spells it, before `attach` adds an arm's prefix."""
    return name.split("/", 1)[-1]


def add_servos(
    spec: mujoco.MjSpec,
    arm: ArmDescription,
    armature: float | None,
    gravity_compensation: bool = True,
) -> None:
    """A position servo per arm joint, named as the joint, with the arm's gains and torque
    limits (the joints' armature set, or the model's own kept if None). With
    `gravity_compensation` the servo cancels the arm's weight (actuatorgravcomp), which counts
    against the same limit instead of being a free torque; without, it holds the weight by
    its position error, as a hobby servo does, and sags."""
    for joint_name, kp, damping, torque in zip(arm.joints, arm.kp, arm.damping, arm.torque_limits):
        joint = spec.joint(local(joint_name))
        if armature is not None:
            joint.armature = armature
        joint.damping = [damping, 0.0, 0.0]
        act = spec.add_actuator(
            name=local(joint_name), target=local(joint_name), trntype=mujoco.mjtTrn.mjTRN_JOINT
        )
        act.set_to_position(kp=kp, kv=0.0)
        act.ctrlrange = joint.range
        act.ctrllimited = True
        act.forcerange = [-torque, torque]
        act.forcelimited = True
        joint.actgravcomp = gravity_compensation
        joint.actfrcrange = [-torque, torque]
        joint.actfrclimited = True


def tune_pads(spec: mujoco.MjSpec, pads: list[mujoco.MjsGeom], grip: GripperConfig) -> None:
    """The pads' own friction, torsional friction, stiff contact and a priority over bricks,
    so a held brick does not creep and the bricks' friction stays out of the grip."""
    for pad in pads:
        pad.friction = [grip.pad_friction, 0.02, 0.0002]
        pad.condim = 4
        pad.priority = 1
        pad.solref = list(PAD_SOLREF)
        pad.solimp = list(PAD_SOLIMP)
        pad.rgba = [0.15, 0.15, 0.15, 1]


def add_gripper_servo(
    spec: mujoco.MjSpec, arm: ArmDescription, robot: RobotDescription, grip: GripperConfig
) -> None:
    """One servo on a tendon summing both fingers' opening travel (command = finger gap less
    the closed width), force-limited to the grip force, stiff enough that any command short of
    the brick saturates at that limit."""
    tendon = spec.add_tendon(name=local(arm.gripper_actuator) + "_gap")
    for joint_name, gain in zip(arm.finger_joints, robot.finger_gains):
        tendon.wrap_joint(local(joint_name), float(gain))
    act = spec.add_actuator(
        name=local(arm.gripper_actuator),
        target=local(arm.gripper_actuator) + "_gap",
        trntype=mujoco.mjtTrn.mjTRN_TENDON,
    )
    act.set_to_position(kp=grip.stiffness, kv=GRIPPER_DAMPING)
    act.ctrlrange = [0.0, 2 * robot.finger_stroke]
    act.ctrllimited = True
    act.forcerange = [-grip.force, grip.force]
    act.forcelimited = True
