"""The Panda pair's model: example-robot-data's panda.urdf, once per arm, attached as `left/`
and `right/` at the preset's bases, each on a pedestal.

What is changed from the URDF, and why:
- each finger mounted 12 mm further out along its own sliding axis (spacers: the brick is
  86 mm wide, the stock hand opens 80 mm), the finger joints keeping the real 0-40 mm;
- one force-limited position servo on a tendon across both fingers (common.py), the URDF's
  <mimic> kept as a joint equality, stiffened, so the fingers stay symmetric;
- position servos on the arm joints with the real arm's torque limits, armature 0.1, the
  preset's damping, and gravity compensation counted against the limits;
- the rubber finger tips are the pads (common.py);
- drawn with its visual meshes and colours (converted from the .dae files, which MuJoCo cannot
  read, by scripts/convert_panda_meshes.py), the collision geometry hidden from the camera.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import mujoco
import numpy as np

from ...config import SimConfig
from ...resources import ASSETS
from ...robots import ArmDescription, RobotDescription
from .common import (
    VISUAL_GROUP,
    add_gripper_servo,
    add_servos,
    add_tool,
    hide_collision_geoms,
    local,
    robots_dir,
    tune_finger,
    tune_pads,
)

VISUALS = ASSETS / "robots" / "panda" / "meshes" / "visual"
ARMATURE = 0.1
PEDESTAL = (0.11, 0.3355)  # m, radius and half height: from the floor to the base


def arm_spec(arm: ArmDescription, robot: RobotDescription, config: SimConfig) -> mujoco.MjSpec:
    """One Panda with the changes listed in this module's docstring, its names unprefixed."""
    root = robots_dir() / "panda_description"
    text = (root / "urdf" / "panda.urdf").read_text()
    meshes = root / "meshes" / "collision"
    # Absolute mesh paths survive attach() and to_xml(); the .dae visuals are discarded.
    text = text.replace(
        "package://example-robot-data/robots/panda_description/meshes/collision/", f"{meshes}/"
    )
    compiler = '<mujoco><compiler fusestatic="false" discardvisual="true"/></mujoco>'
    robot_tag_end = text.index(">", text.index("<robot")) + 1
    spec = mujoco.MjSpec.from_string(text[:robot_tag_end] + compiler + text[robot_tag_end:])
    add_servos(spec, arm, ARMATURE)
    for body in spec.bodies:
        if body.name.startswith("panda_") and body.name != local(arm.root_body):
            body.gravcomp = 1.0
    _fit_fingers(spec, arm, robot)
    tune_pads(spec, [spec.geom(local(p)) for p in arm.pads], config.gripper)
    add_gripper_servo(spec, arm, robot, config.gripper)
    add_tool(spec.body("panda_hand_tcp"), arm)
    hide_collision_geoms(spec)
    _add_visual_meshes(spec)
    return spec


def _add_visual_meshes(spec: mujoco.MjSpec) -> None:
    """Each link's visual meshes, one a colour, where its collision mesh is: drawn only, no
    contact and no mass (the URDF's inertials stay the links' own). The fingers collide as
    boxes, not a mesh: their visual meshes go in the finger frames as the URDF places them
    (the right finger's turned half round z), so a wrist camera sees the fingers."""
    parts = json.loads((VISUALS / "parts.json").read_text())
    for geom in [g for g in spec.geoms if g.type == mujoco.mjtGeom.mjGEOM_MESH]:
        _add_visual(spec, geom.parent, parts.get(geom.meshname, ()), geom.pos, geom.quat)
    for finger, quat in FINGER_VISUALS.items():
        _add_visual(spec, spec.body(finger), parts["finger"], [0.0, 0.0, 0.0], quat)


# The finger bodies and their visual meshes' orientation in them (the URDF's <visual> origin).
FINGER_VISUALS = {
    "panda_leftfinger": [1.0, 0.0, 0.0, 0.0],
    "panda_rightfinger": [0.0, 0.0, 0.0, 1.0],
}


def _add_visual(spec: mujoco.MjSpec, body: mujoco.MjsBody, parts: Any, pos: Any, quat: Any) -> None:
    """A part's visual meshes (file, colour) on `body` at `pos`, `quat`: drawn only."""
    for file, rgba in parts:
        mesh = f"visual_{Path(file).stem}"
        if spec.mesh(mesh) is None:
            spec.add_mesh(name=mesh, file=str(VISUALS / file))
        body.add_geom(
            type=mujoco.mjtGeom.mjGEOM_MESH,
            meshname=mesh,
            pos=pos,
            quat=quat,
            contype=0,
            conaffinity=0,
            group=VISUAL_GROUP,
            rgba=rgba,
            density=0,
            mass=0,
        )


def _fit_fingers(spec: mujoco.MjSpec, arm: ArmDescription, robot: RobotDescription) -> None:
    spacer = robot.closed_width / 2  # the stock fingers meet at zero travel
    for joint_name, body_name, pad_name in zip(arm.finger_joints, arm.finger_bodies, arm.pads):
        joint = spec.joint(local(joint_name))
        joint.range = [0.0, robot.finger_stroke]
        tune_finger(joint)
        body = spec.body(local(body_name))
        body.pos = np.array(body.pos) + spacer * np.array(joint.axis)
        body.geoms[3].name = local(pad_name)  # the URDF's "rubber tip with which to grasp"
    # The URDF's <mimic> arrives as a joint equality; stiffen it so the fingers stay symmetric.
    for eq in spec.equalities:
        if eq.type == mujoco.mjtEq.mjEQ_JOINT:
            eq.solref = [0.005, 1.0]


def add_panda_pair(spec: mujoco.MjSpec, config: SimConfig, robot: RobotDescription) -> None:
    """Both Pandas into the scene, each on its pedestal at its base."""
    for name, arm in robot.arms.items():
        x, y, z = arm.base
        spec.worldbody.add_geom(
            name=f"{name}_pedestal",
            type=mujoco.mjtGeom.mjGEOM_CYLINDER,
            size=[*PEDESTAL, 0],
            pos=[x, y, z - PEDESTAL[1]],
            material="pedestal",
        )
        frame = spec.worldbody.add_frame(pos=list(arm.base))
        spec.attach(arm_spec(arm, robot, config), prefix=f"{name}/", frame=frame)
