"""What pyramid_sim needs to know of a robot, as plain values: a preset per robot.

The scheduler, the primitives and the IK speak of arms as "left" and "right" and of logical
parts (joints, tool point, fingers, pads); a description maps those to the model's own names
and carries the real robot's limits and dimensions. Pure: no MuJoCo. The physics side
(`physics/robot_models/`) builds the model a description names.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

from ..choices import RobotName

Vec3 = tuple[float, float, float]


@dataclass(frozen=True)
class ArmDescription:
    """One arm with its hand: model names, and the real arm's limits shoulder to wrist."""

    joints: tuple[str, ...]
    velocity_limits: tuple[float, ...]  # rad/s
    torque_limits: tuple[float, ...]  # N m, gravity compensation included
    acceleration_limits: tuple[float, ...]  # rad/s^2
    kp: tuple[float, ...]  # N m/rad, the position servos
    damping: tuple[float, ...]  # N m s/rad
    home: tuple[float, ...]  # rad: a comfortable posture, hand down in front of the robot
    base: Vec3  # m, where the arm stands in the world: a one-arm build is centred in front
    root_body: str  # every body of the arm and its hand hangs below this one
    tcp_site: str  # the tool centre point: z out of the hand, fingers closing along y
    zone_bodies: tuple[str, ...]  # whose positions tell whether the arm is in the shared zone
    guarded_bodies: tuple[str, ...]  # links the IK keeps off the other arm and the robot's body
    finger_joints: tuple[str, ...]  # two sliding fingers, or one jaw against a fixed one
    finger_bodies: tuple[str, ...]
    pads: tuple[str, str]  # the geoms that touch the brick
    gripper_actuator: str
    yaw_reference: float = 0.0  # rad: grasps take the hand yaw nearer this of the two that fit,
    # and the clear pose this yaw, so the last wrist joint stays inside its range
    twist_pair: tuple[int, int] | None = None  # two joints (0-based) whose axes line up when
    # the shoulder stands upright: the expert's IK damps their turn against each other

    @property
    def wrist_camera(self) -> str:
        """The camera on the hand, beside the tool centre point, looking along the fingers."""
        return f"{self.tcp_site}_camera"

    def __post_init__(self) -> None:
        n = len(self.joints)
        for name in (
            "velocity_limits",
            "torque_limits",
            "acceleration_limits",
            "kp",
            "damping",
            "home",
        ):
            if len(getattr(self, name)) != n:
                raise ValueError(f"{name}: {len(getattr(self, name))} values for {n} joints")
        if self.twist_pair is not None and not all(0 <= i < n for i in self.twist_pair):
            raise ValueError(f"twist_pair: {self.twist_pair}; accepted joints 0-{n - 1}")


@dataclass(frozen=True)
class RobotDescription:
    """A robot preset: its two arms, its gripper's geometry and where things stand."""

    name: RobotName
    summary: str
    arms: Mapping[str, ArmDescription]  # "left" and "right"
    finger_stroke: float  # m the gap opens, halved: each finger's travel in a two-finger hand
    finger_gains: tuple[float, ...]  # m of gap a unit of each finger joint's travel opens:
    # +1 or -1 for a sliding finger, a hinged jaw's lever (m/rad)
    closed_width: float  # m between the pads with both fingers closed (spacers or slots set it)
    open_margin: float  # m short of its end each open finger stops: a knock then pushes it
    # against its servo, not into its joint stop
    grasp_height: float  # m above a brick's centre the tool point grips it
    clear_pose: Vec3  # x, |y| and z of each arm's outer collision-clear pose, out to its side
    static_bodies: tuple[str, ...]  # the robot's own body (torso, head): kept off by the IK
    posture_cost: float = 1e-2  # of the IK's pull towards home: too high and it stalls short
    max_speed: float = float("inf")  # m/s: caps the motion settings' free-move speed,
    max_slow_speed: float = float("inf")  # their servo speed near bricks,
    max_turn_rate: float = float("inf")  # and the hand's turn rate (rad/s)
    hand_acceleration: float = float("inf")  # m/s^2: how fast the `waypoint` and `anchored`
    # modes' hand target gains and sheds its speed (inf: at once, within a control step)
    hand_modes_acceleration_share: float | None = None  # of the joints' acceleration limits,
    # the motion generator's behind the hand modes' IK (None: the generator's own share)
    gravity_compensation: bool = True  # the servos hold the arm's weight for free (a Panda's,
    # Baxter's controllers); where False they hold it within their torque, and sag
    pick_clearance: float = 0.0  # m the tool point stands off a brick's centre towards the
    # fixed jaw's side (tool -y) until the grip: a one-jaw hand cannot open that side
    # As lerobot records this robot (learning/task/lerobot_units.py): its robot_type, each arm's
    # motors by lerobot's names (joints in degrees, the gripper 0-100 over the jaw's joint
    # range `lerobot_gripper_span`, rad). Empty: pyramid_sim's own names and SI units.
    lerobot_robot_type: str = ""
    lerobot_motors: tuple[str, ...] = ()
    lerobot_gripper_span: tuple[float, float] = (0.0, 0.0)
    length_scale: float = 1.0  # its lengths against DE NIRO's: how far the learning layouts
    # move the spot and the structure, and how clear of the spot they keep
    scale: Mapping[str, Mapping[str, Any]] = field(default_factory=dict)  # SimConfig sections
    # defaults at this robot's scale ({"brick": {"width": ...}, ...}); empty: DE NIRO's

    def __post_init__(self) -> None:
        object.__setattr__(self, "arms", MappingProxyType(dict(self.arms)))
        object.__setattr__(
            self, "scale", MappingProxyType({k: dict(v) for k, v in self.scale.items()})
        )
        if set(self.arms) != {"left", "right"}:
            raise ValueError(f"arms: {sorted(self.arms)}; a preset has a left and a right arm")

    @property
    def one_jaw(self) -> bool:
        """A hand of one moving jaw against a fixed one (the SO-101's), not two fingers."""
        return len(self.arms["left"].finger_joints) == 1

    def open_gap(self) -> float:
        """The finger-gap command (both fingers' joint travel, m) that opens the hand."""
        return 2 * (self.finger_stroke - self.open_margin)

    def squeeze_gap(self, brick_width: float, force: float, stiffness: float) -> float:
        """The gap command at which the pads press a brick `brick_width` wide with `force`."""
        return brick_width - self.closed_width - force / stiffness
