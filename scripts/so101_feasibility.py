"""Feasibility of an SO-101 pair preset, measured before building it.

One vendored SO-101 picks a 45 x 20 x 14.5 mm, 15 g brick top-down by friction alone and
places it 12 cm away turned 0.5 rad, driven by mink's IK on its 5 arm joints. The jaws' mesh
hulls (which fill the gap between the jaws) do not collide; thin pads on the tips' inner faces
do. The arm's servos are position servos of stiffness `--kp` limited to the STS3215's 12 V
stall torque, with no gravity compensation (the real arm has none); `--precompensate` offsets
each command by the model's gravity torque over kp, a controller's choice a real arm could
make too. The yaw is commanded at once (no turn-rate ramp), so the wrist roll's servo
saturates for a moment: a limit of this script, not of the arm.

    python3 scripts/so101_feasibility.py [--kp 50] [--precompensate] [--grip-force 10]

Results: docs/notes/2026-11-25-so101-groundwork.md.
"""

from __future__ import annotations

import argparse
import math

import mink
import mujoco
import numpy as np

from pyramid_sim.resources import ASSETS

XML = ASSETS / "robots" / "so101" / "so101.xml"
ARM = ("shoulder_pan", "shoulder_lift", "elbow_flex", "wrist_flex", "wrist_roll")
STALL_TORQUE = 2.94  # N m, STS3215 at 12 V (docs/notes/2026-11-25-so101-groundwork.md)
BRICK = (0.045, 0.020, 0.0145)  # m: DE NIRO's proportions at the jaw's scale
BRICK_MASS = 0.015  # kg
JAW_LEVER = 0.0728  # m of tip gap a radian of the jaw joint, near parallel (measured)
PARALLEL_GAP = 0.0155  # m between the tips' inner faces at jaw angle 0
FIXED_FACE_X, MOVING_FACE_X = -0.0080, 0.0079  # m, the tips' inner faces in the gripper frame
PAD_HALF = (0.0005, 0.007, 0.008)  # m: thickness, width (gripper y), length (gripper z)
PAD_Z = -0.0955  # m, the pads' centre in the gripper frame
GRASP_Z = 0.010  # m, the tool point above the table: the pads' lower ends 2 mm above it
HOVER = 0.035  # m above the grasp
START, GOAL, GOAL_YAW = (0.20, 0.06), (0.20, -0.06), 0.5
DT = 0.01  # s, the IK's step
DOWN = np.array([[1.0, 0, 0], [0, -1, 0], [0, 0, -1]])  # tool z down, tool y along world -y


def build(kp: float, grip_force: float) -> mujoco.MjModel:
    spec = mujoco.MjSpec.from_file(str(XML))
    spec.option.timestep = 0.002
    spec.option.cone = mujoco.mjtCone.mjCONE_ELLIPTIC
    spec.option.impratio = 10
    for actuator in list(spec.actuators):
        spec.delete(actuator)
    gripper, jaw = spec.body("gripper"), spec.body("moving_jaw_so101_v1")
    for geom in [*gripper.geoms, *jaw.geoms]:
        geom.contype = geom.conaffinity = 0  # the hulls fill the gap between the jaws
    _add_pads(spec, gripper, jaw)
    tool = np.column_stack([[0, 1, 0], [1, 0, 0], [0, 0, -1]])  # z along the jaws, y closing
    quat = np.zeros(4)
    mujoco.mju_mat2Quat(quat, tool.flatten())
    held_centre = FIXED_FACE_X + BRICK[1] / 2
    gripper.add_site(name="tcp", pos=[held_centre, -0.0002, PAD_Z], quat=quat)
    for name in ARM:
        act = spec.add_actuator(name=name, target=name, trntype=mujoco.mjtTrn.mjTRN_JOINT)
        act.set_to_position(kp=kp, kv=0.0)
        act.forcerange = [-STALL_TORQUE, STALL_TORQUE]
        act.forcelimited = True
        act.ctrlrange = spec.joint(name).range
        act.ctrllimited = True
    spec.joint("gripper").range = [0.0, 1.745]
    tendon = spec.add_tendon(name="gap")
    tendon.wrap_joint("gripper", JAW_LEVER)
    act = spec.add_actuator(name="gripper", target="gap", trntype=mujoco.mjtTrn.mjTRN_TENDON)
    act.set_to_position(kp=2000.0, kv=10.0)
    act.forcerange = [-grip_force, grip_force]
    act.forcelimited = True
    act.ctrlrange = [0.0, JAW_LEVER * 1.745]
    act.ctrllimited = True
    spec.worldbody.add_geom(
        type=mujoco.mjtGeom.mjGEOM_BOX,
        size=[0.4, 0.4, 0.01],
        pos=[0.2, 0, -0.01],
        friction=[1, 0.005, 0.0001],
    )
    brick = spec.worldbody.add_body(name="brick", pos=[*START, BRICK[2] / 2])
    brick.add_freejoint()
    brick.add_geom(
        type=mujoco.mjtGeom.mjGEOM_BOX,
        size=[s / 2 for s in BRICK],
        mass=BRICK_MASS,
        friction=[1, 0.005, 0.0001],
    )
    return spec.compile()


def _add_pads(spec: mujoco.MjSpec, gripper: mujoco.MjsBody, jaw: mujoco.MjsBody) -> None:
    """A thin pad on each tip's inner face, placed in the gripper frame at jaw angle 0."""
    model = spec.compile()
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    g, j = model.body("gripper").id, model.body("moving_jaw_so101_v1").id
    rot_g, rot_j = data.xmat[g].reshape(3, 3), data.xmat[j].reshape(3, 3)
    gripper.add_geom(
        name="fixed_pad",
        type=mujoco.mjtGeom.mjGEOM_BOX,
        size=PAD_HALF,
        pos=[FIXED_FACE_X - PAD_HALF[0], -0.0002, PAD_Z],
    )
    world = data.xpos[g] + rot_g @ np.array([MOVING_FACE_X + PAD_HALF[0], -0.0002, PAD_Z])
    quat = np.zeros(4)
    mujoco.mju_mat2Quat(quat, (rot_j.T @ rot_g).flatten())
    jaw.add_geom(
        name="moving_pad",
        type=mujoco.mjtGeom.mjGEOM_BOX,
        size=PAD_HALF,
        pos=rot_j.T @ (world - data.xpos[j]),
        quat=quat,
    )
    for name in ("fixed_pad", "moving_pad"):
        pad = spec.geom(name)
        pad.friction = [1.0, 0.02, 0.0002]
        pad.condim = 4
        pad.priority = 1
        pad.solref = [0.004, 1]
        pad.solimp = [0.99, 0.999, 0.0005, 0.5, 2]


class Run:
    """The arm driven through poses of its tool point, measuring torque peaks."""

    def __init__(self, model: mujoco.MjModel, kp: float, precompensate: bool) -> None:
        self.model, self.kp, self.precompensate = model, kp, precompensate
        self.data = mujoco.MjData(model)
        self.arm_q = [model.joint(n).qposadr[0] for n in ARM]
        self.arm_v = [model.joint(n).dofadr[0] for n in ARM]
        self.acts = [model.actuator(n).id for n in ARM]
        self.grip = model.actuator("gripper").id
        self.tcp = model.site("tcp").id
        self.brick = model.body("brick").id
        self.data.qpos[self.arm_q] = [0, -1.0, 1.0, 1.5, 0]
        self.data.qpos[model.joint("gripper").qposadr[0]] = 0.5
        mujoco.mj_forward(model, self.data)
        self.config = mink.Configuration(model)
        self.config.update(self.data.qpos.copy())
        self.task = mink.FrameTask("tcp", "site", position_cost=1.0, orientation_cost=0.3)
        self.posture = mink.PostureTask(model, cost=1e-3)
        self.posture.set_target_from_configuration(self.config)
        self.limits = [mink.ConfigurationLimit(model)]
        self.peak = np.zeros(len(ARM))

    def command(self, q: np.ndarray) -> np.ndarray:
        """The servos' targets: the IK's joints, or offset by gravity torque over kp."""
        if not self.precompensate:
            return q
        probe = mujoco.MjData(self.model)
        probe.qpos[:] = self.data.qpos
        probe.qpos[self.arm_q] = q
        mujoco.mj_forward(self.model, probe)
        return q + probe.qfrc_bias[self.arm_v] / self.kp

    def move(
        self,
        xy: tuple[float, float] | np.ndarray,
        z: float,
        yaw: float,
        gap: float,
        seconds: float,
        speed: float = 0.08,
    ) -> None:
        """A smooth straight move of the tool point to (xy, z) at `yaw`, the jaw at `gap`."""
        start = self.data.site_xpos[self.tcp].copy()
        end = np.array([*xy, z])
        duration = max(float(np.linalg.norm(end - start)) / speed, 0.2)
        cos, sin = math.cos(yaw), math.sin(yaw)
        rotation = np.array([[cos, -sin, 0], [sin, cos, 0], [0, 0, 1]]) @ DOWN
        for k in range(int(seconds / DT)):
            t = min(1.0, (k + 1) * DT / duration)
            t = t * t * (3 - 2 * t)
            pose = mink.SE3.from_rotation_and_translation(
                mink.SO3.from_matrix(rotation), start + t * (end - start)
            )
            self.task.set_target(pose)
            velocity = mink.solve_ik(
                self.config, [self.task, self.posture], DT, "daqp", damping=1e-3, limits=self.limits
            )
            self.config.integrate_inplace(velocity, DT)
            self.data.ctrl[self.acts] = self.command(self.config.q[self.arm_q])
            self.data.ctrl[self.grip] = gap
            for _ in range(int(round(DT / self.model.opt.timestep))):
                mujoco.mj_step(self.model, self.data)
                torque = np.abs(self.data.actuator_force[self.acts])
                self.peak = np.maximum(self.peak, torque)


def aside(xy: tuple[float, float], yaw: float, margin: float) -> np.ndarray:
    """`xy` moved `margin` towards the fixed jaw's side (tool -y), so that jaw clears."""
    tool_y = -np.array([-math.sin(yaw), math.cos(yaw)])  # DOWN maps tool y to world -y
    return np.asarray(xy) - margin * tool_y


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--kp", type=float, default=50.0, help="servo stiffness, N m/rad")
    parser.add_argument("--precompensate", action="store_true")
    parser.add_argument("--grip-force", type=float, default=10.0, help="N")
    args = parser.parse_args()
    run = Run(build(args.kp, args.grip_force), args.kp, args.precompensate)
    opened = JAW_LEVER * 0.6
    squeeze = BRICK[1] - PARALLEL_GAP - args.grip_force / 2000.0
    run.move(START, GRASP_Z + HOVER, 0.0, opened, 2.5)
    run.peak[:] = 0.0  # from here on: the first move starts far from its target
    run.move(aside(START, 0.0, 0.004), GRASP_Z + HOVER, 0.0, opened, 1.0, speed=0.03)
    run.move(aside(START, 0.0, 0.004), GRASP_Z, 0.0, opened, 1.5, speed=0.03)
    run.move(aside(START, 0.0, 0.0005), GRASP_Z, 0.0, opened, 0.8, speed=0.01)
    sag = np.linalg.norm(run.data.site_xpos[run.tcp] - run.config.data.site_xpos[run.tcp])
    run.move(aside(START, 0.0, 0.0005), GRASP_Z, 0.0, squeeze, 1.5)
    held = run.data.xpos[run.brick] - run.data.site_xpos[run.tcp]
    run.move(aside(START, 0.0, 0.0005), GRASP_Z + HOVER, 0.0, squeeze, 1.5, speed=0.03)
    run.move(GOAL, GRASP_Z + HOVER, GOAL_YAW, squeeze, 3.0)
    slip = np.linalg.norm(run.data.xpos[run.brick] - run.data.site_xpos[run.tcp] - held)
    run.move(GOAL, GRASP_Z + 0.002, GOAL_YAW, squeeze, 1.5, speed=0.03)
    run.move(GOAL, GRASP_Z + 0.002, GOAL_YAW, opened, 0.6)
    run.move(GOAL, GRASP_Z + HOVER, GOAL_YAW, opened, 1.0, speed=0.03)
    placed = run.data.xpos[run.brick]
    matrix = run.data.xmat[run.brick]
    print(
        f"kp {args.kp:g}, precompensate {args.precompensate}, grip force {args.grip_force:g} N: "
        f"tool point {sag * 1000:.2f} mm off the IK's at the grasp, slip in hand "
        f"{slip * 1000:.2f} mm, placed {np.linalg.norm(placed[:2] - GOAL) * 1000:.2f} mm from "
        f"the goal turned {math.degrees(math.atan2(matrix[3], matrix[0])):.1f} deg (asked "
        f"{math.degrees(GOAL_YAW):.1f}), resting {placed[2] * 1000:.1f} mm high (asked "
        f"{BRICK[2] / 2 * 1000:.2f}), torque peaks {np.round(run.peak, 2).tolist()} N m "
        f"(limit {STALL_TORQUE})"
    )


if __name__ == "__main__":
    main()
