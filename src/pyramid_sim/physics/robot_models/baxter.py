"""Baxter's model: the shipped baxter.urdf (assets/robots/baxter/, from example-robot-data) with
its meshes converted to STL, standing at the world origin (its base frame is DE NIRO's).

What is changed from the URDF, and why:
- the head is locked (head_pan removed): nothing in a build turns it;
- the 1 mm placeholder spheres (head, screen, sonar ring) do not collide; the 0.22 m head
  padding spheres do (not drawn), and the IK keeps the arms off them, the torso and the
  pedestal;
- per arm nine body pairs that touch at any posture by construction do not collide (torso with
  the upper shoulder, lower shoulder and upper elbow; upper shoulder with upper elbow; the
  elbow and forearm "visual" links with their neighbours; finger with finger). The SRDF's 398
  disabled pairs are not taken: 85 of them are left-right pairs and would hide arm-arm contacts;
- the fingers are mounted in slot 4 (+-17.5 mm, as the real gripper's slots allow): they open
  to 95.7 mm and grip the 86 mm brick at 16 mm of their 20.8 mm travel; slot 2 (the URDF's)
  opens 57.7 mm. Paddle tips on both hands (the right hand's half-round tips leave no travel);
- the two fingers kept symmetric by a joint equality, and driven by one force-limited servo
  on a tendon across both (common.py); position servos with the URDF's torque limits, gravity
  compensation counted against them; the pads are the paddle tips' contact boxes.
"""

from __future__ import annotations

import re

import mujoco

from ...config import SimConfig
from ...resources import ASSETS
from ...robots import ArmDescription, RobotDescription
from ...robots.baxter import PREFIX
from .common import (
    add_gripper_servo,
    add_servos,
    add_tool,
    hide_collision_geoms,
    local,
    tune_finger,
    tune_pads,
)

HERE = ASSETS / "robots" / "baxter"
MESH_URL = r"package://example-robot-data/robots/baxter_description/meshes/([^\"]+)\.DAE"
ARMATURE = 0.1
SLOT_4 = 0.0175  # m: a finger's mount off the gripper's centre line, (slot - 1) 9.5 mm - 11 mm
PADDLE = {"size": [0.021, 0.00325, 0.0185], "pos": (0.0, 0.0045, -0.015)}  # the tip's box
# Body pairs that touch by construction, per arm ("{s}" the side, "{g}" the gripper's letter).
EXCLUDED = (
    ("torso", "{s}_upper_shoulder"),
    ("torso", "{s}_lower_shoulder"),
    ("torso", "{s}_upper_elbow"),
    ("{s}_upper_shoulder", "{s}_upper_elbow"),
    ("{s}_lower_elbow", "{s}_upper_elbow_visual"),
    ("{s}_upper_forearm", "{s}_upper_elbow_visual"),
    ("{s}_lower_forearm", "{s}_upper_forearm_visual"),
    ("{s}_wrist", "{s}_upper_forearm_visual"),
    ("{g}_gripper_l_finger", "{g}_gripper_r_finger"),
)


def baxter_spec() -> mujoco.MjSpec:
    """The URDF with the shipped STL meshes, its head locked and placeholders inert."""
    text = (HERE / "baxter.urdf").read_text()
    text = re.sub(MESH_URL, lambda m: str(HERE / "meshes" / f"{m.group(1)}.stl"), text)
    compiler = '<mujoco><compiler fusestatic="false" discardvisual="false"/></mujoco>'
    end = text.index(">", text.index("<robot")) + 1
    spec = mujoco.MjSpec.from_string(text[:end] + compiler + text[end:])
    spec.delete(spec.joint("head_pan"))
    for geom in spec.geoms:
        if geom.type == mujoco.mjtGeom.mjGEOM_SPHERE and geom.size[0] < 0.002:
            geom.contype = geom.conaffinity = 0
    for padding in ("collision_head_link_1", "collision_head_link_2"):
        for geom in spec.body(padding).geoms:
            geom.group = 3  # drawn, the padding hides the head; group 3 is not drawn
    return spec


def _fit_gripper(spec: mujoco.MjSpec, side: str, arm: ArmDescription) -> None:
    g = side[0]
    for joint_name, finger, sign in zip(arm.finger_joints, ("l", "r"), (1, -1)):
        body = spec.body(f"{g}_gripper_{finger}_finger")
        body.pos = [body.pos[0], sign * SLOT_4, body.pos[2]]
        joint = spec.joint(local(joint_name))
        tune_finger(joint)
        tip = spec.body(f"{g}_gripper_{finger}_finger_tip")
        pad = next(geo for geo in tip.geoms if geo.contype or geo.conaffinity)
        pad.name = local(arm.pads[0 if finger == "l" else 1])
        pad.type = mujoco.mjtGeom.mjGEOM_BOX  # the right hand's half-round tips are cylinders
        pad.size = PADDLE["size"]
        x, y, z = PADDLE["pos"]
        pad.pos = [x, -sign * y, z]
        for visual in tip.geoms:
            if visual.type == mujoco.mjtGeom.mjGEOM_MESH:
                visual.meshname = _paddle_mesh(spec)
    equality = spec.add_equality(
        type=mujoco.mjtEq.mjEQ_JOINT,
        name1=local(arm.finger_joints[0]),
        name2=local(arm.finger_joints[1]),
    )
    equality.data[:5] = [0.0, -1.0, 0.0, 0.0, 0.0]  # right = -left: the fingers move as one
    equality.solref = [0.005, 1.0]


def _paddle_mesh(spec: mujoco.MjSpec) -> str:
    """The name of the paddle tip's mesh asset (the left hand's tips use it)."""
    return next(m.name for m in spec.meshes if "paddle_tip" in m.file)


def add_baxter(spec: mujoco.MjSpec, config: SimConfig, robot: RobotDescription) -> None:
    """Baxter at the world origin, with the changes listed in this module's docstring."""
    body = baxter_spec()
    for side, arm in robot.arms.items():
        g = side[0]
        for first, second in EXCLUDED:
            body.add_exclude(
                bodyname1=first.format(s=side, g=g), bodyname2=second.format(s=side, g=g)
            )
        add_servos(body, arm, ARMATURE)
        mount = body.body(local(arm.root_body))
        for link in _subtree(mount):
            link.gravcomp = 1.0
        _fit_gripper(body, side, arm)
        tune_pads(body, [body.geom(local(p)) for p in arm.pads], config.gripper)
        add_gripper_servo(body, arm, robot, config.gripper)
        add_tool(body.body(f"{side}_gripper"), arm)
    hide_collision_geoms(body)  # the URDF's visual meshes show the robot
    spec.attach(body, prefix=PREFIX, frame=spec.worldbody.add_frame(pos=[0.0, 0.0, 0.0]))


def _subtree(body: mujoco.MjsBody) -> list[mujoco.MjsBody]:
    found = [body]
    for child in body.bodies:
        found += _subtree(child)
    return found
