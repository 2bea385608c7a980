"""The SO-101 pair's model: the vendored so101.xml (assets/robots/so101/), once per arm,
attached as `left/` and `right/` at the preset's bases on the table top.

What is changed from the vendored model, and why (measured in
docs/notes/2026-11-25-so101-groundwork.md):
- the jaws' mesh hulls do not collide: a hull fills the gap between the jaws, so no brick
  would fit; two thin pads on the tips' inner faces do (common.py's pad contact), and the
  model's own inert pads go;
- the shipped actuators go: position servos with the STS3215's 12 V stall torque and no
  gravity compensation (the real servo holds the arm's weight within its own torque), and one
  force-limited servo on a tendon across the jaw (common.py), the jaw's travel a subset of its
  real range;
- a tool point between the pads, where a held brick's centre is, and a wrist camera on the
  hand; the scene's cameras a third as far from the work.
"""

from __future__ import annotations

import mujoco
import numpy as np

from ...config import SimConfig
from ...resources import ASSETS
from ...robots import ArmDescription, RobotDescription
from .common import add_gripper_servo, add_servos, hide_collision_geoms, local, tune_pads

XML = ASSETS / "robots" / "so101" / "so101.xml"
HAND, JAW = "gripper", "moving_jaw_so101_v1"
# The tips' inner faces in the hand's frame with the jaw at 0 (parallel), and the pads on them.
FIXED_FACE_X, MOVING_FACE_X = -0.0080, 0.0079  # m
PAD_HALF = (0.0005, 0.007, 0.008)  # m: thickness, width, length along the jaw
PAD_Y, PAD_Z = -0.0002, -0.0955  # m
# The tool frame in the hand's: z along the jaws towards the tips, y the way they close.
TOOL_AXES = np.column_stack([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])
# The wrist camera in the tool frame: beside the hand, where the jaws do not close, behind the
# tips, looking at a point just ahead of the tool point.
CAMERA_AT, CAMERA_LOOKS_AT, CAMERA_FOVY = (0.06, 0.0, -0.05), (0.0, 0.0, 0.01), 70.0


def arm_spec(arm: ArmDescription, robot: RobotDescription, config: SimConfig) -> mujoco.MjSpec:
    """One SO-101 with the changes listed in this module's docstring, its names unprefixed."""
    spec = mujoco.MjSpec.from_file(str(XML))
    for mesh in spec.meshes:  # absolute, as `scene --out x.xml` copies them (scene_files.py)
        mesh.file = str(XML.parent / spec.meshdir / mesh.file)
    for actuator in list(spec.actuators):
        spec.delete(actuator)
    hand, jaw = spec.body(HAND), spec.body(JAW)
    for geom in [*hand.geoms, *jaw.geoms]:
        if geom.name in ("fixed_jaw_pad", "moving_jaw_pad"):
            spec.delete(geom)
        elif geom.contype or geom.conaffinity:
            geom.contype = geom.conaffinity = 0
    _add_pads(spec, hand, jaw, arm)
    tune_pads(spec, [spec.geom(local(p)) for p in arm.pads], config.gripper)
    held_centre = FIXED_FACE_X + config.brick.width / 2  # a held brick lies on the fixed pad
    _add_tool(hand, arm, [held_centre, PAD_Y, PAD_Z])
    add_servos(spec, arm, armature=None, gravity_compensation=robot.gravity_compensation)
    (jaw_joint,) = arm.finger_joints
    spec.joint(local(jaw_joint)).range = [0.0, 2 * robot.finger_stroke / robot.finger_gains[0]]
    add_gripper_servo(spec, arm, robot, config.gripper)
    hide_collision_geoms(spec)
    return spec


def _add_pads(
    spec: mujoco.MjSpec, hand: mujoco.MjsBody, jaw: mujoco.MjsBody, arm: ArmDescription
) -> None:
    """A thin pad on each tip's inner face, placed in the hand's frame with the jaw at 0."""
    model = spec.compile()
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    h, j = model.body(HAND).id, model.body(JAW).id
    rot_h, rot_j = data.xmat[h].reshape(3, 3), data.xmat[j].reshape(3, 3)
    fixed, moving = (local(p) for p in arm.pads)
    hand.add_geom(
        name=fixed,
        type=mujoco.mjtGeom.mjGEOM_BOX,
        size=PAD_HALF,
        pos=[FIXED_FACE_X - PAD_HALF[0], PAD_Y, PAD_Z],
    )
    at = data.xpos[h] + rot_h @ np.array([MOVING_FACE_X + PAD_HALF[0], PAD_Y, PAD_Z])
    quat = np.zeros(4)
    mujoco.mju_mat2Quat(quat, (rot_j.T @ rot_h).flatten())
    jaw.add_geom(
        name=moving,
        type=mujoco.mjtGeom.mjGEOM_BOX,
        size=PAD_HALF,
        pos=rot_j.T @ (at - data.xpos[j]),
        quat=quat,
    )


def _add_tool(hand: mujoco.MjsBody, arm: ArmDescription, at: list[float]) -> None:
    """The tool point and the wrist camera on the hand."""
    quat = np.zeros(4)
    mujoco.mju_mat2Quat(quat, TOOL_AXES.flatten())
    hand.add_site(
        name=local(arm.tcp_site), pos=at, quat=quat, size=[0.003, 0, 0], rgba=[0, 1, 0, 0]
    )
    eye = np.array(CAMERA_AT)
    back = (eye - np.array(CAMERA_LOOKS_AT)) / np.linalg.norm(eye - np.array(CAMERA_LOOKS_AT))
    right = np.array([0.0, 1.0, 0.0])  # the jaws close across the image
    up = np.cross(back, right)
    hand.add_camera(
        name=local(arm.wrist_camera),
        pos=list(np.array(at) + TOOL_AXES @ eye),
        xyaxes=[*(TOOL_AXES @ right), *(TOOL_AXES @ up)],
        fovy=CAMERA_FOVY,
    )


# The scene's cameras frame DE NIRO's workspace; this pair's is about a third of its size, so
# each moves along its own line of sight to about a third of its distance from the work: the
# overview a little less close, so both arms' jaws stay in frame at their clear poses.
WORK, CLOSER = np.array([0.55, 0.0, 0.1]), {"overview": 0.45, "front": 0.35, "top": 0.35}


def add_so101_pair(spec: mujoco.MjSpec, config: SimConfig, robot: RobotDescription) -> None:
    """Both SO-101s into the scene, each standing on the table at its base, and the scene's
    cameras brought closer to their work."""
    for name, arm in robot.arms.items():
        frame = spec.worldbody.add_frame(pos=list(arm.base))
        spec.attach(arm_spec(arm, robot, config), prefix=f"{name}/", frame=frame)
    for camera, closer in CLOSER.items():
        cam = spec.camera(camera)
        cam.pos = WORK + closer * (np.array(cam.pos) - WORK)
