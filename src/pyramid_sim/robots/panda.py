"""Two Franka Pandas from example-robot-data, 0.5 m apart in front of the table: the preset
pyramid_sim began with. Every Panda name, limit and dimension lives here."""

from __future__ import annotations

from ..choices import Arm
from .description import ArmDescription, RobotDescription

# The real Panda's limits (Franka datasheet, also in example-robot-data's URDF).
VELOCITY_LIMITS = (2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61)
TORQUE_LIMITS = (87.0, 87.0, 87.0, 87.0, 12.0, 12.0, 12.0)
ACCELERATION_LIMITS = (15.0, 7.5, 10.0, 12.5, 15.0, 20.0, 20.0)
# Position gains from shoulder to wrist (FINDINGS.md).
KP = (4500.0, 4500.0, 3500.0, 3500.0, 2000.0, 2000.0, 2000.0)
# Joint damping: 10 on the big joints (at 1 or 4, walls built by two arms lost bricks); 2 on the
# wrist, whose 12 N m cannot turn the hand at the IK's speed against 10.
DAMPING = (10.0, 10.0, 10.0, 10.0, 2.0, 2.0, 2.0)
HOME = (0.0, -0.3, 0.0, -2.2, 0.0, 1.9, 0.785)
BASES = {"left": (0.15, 0.25, 0.0), "right": (0.15, -0.25, 0.0)}
HAND = "panda_hand"
FINGERS = ("panda_leftfinger", "panda_rightfinger")
GUARDED = ("panda_link3", "panda_link4", "panda_link5", "panda_link6", "panda_link7", HAND)


def _arm(arm: Arm) -> ArmDescription:
    def name(n: str) -> str:
        return f"{arm}/{n}"  # each Panda is attached with the prefix "left/" or "right/"

    return ArmDescription(
        joints=tuple(name(f"panda_joint{i}") for i in range(1, 8)),
        velocity_limits=VELOCITY_LIMITS,
        torque_limits=TORQUE_LIMITS,
        acceleration_limits=ACCELERATION_LIMITS,
        kp=KP,
        damping=DAMPING,
        home=HOME,
        twist_pair=(0, 2),  # joints 1 and 3, in line when joint 2 stands at 0
        base=BASES[arm],
        root_body=name("panda_link0"),
        tcp_site=name("tcp"),
        zone_bodies=(name(HAND), name("panda_link6"), name("panda_link4")),
        guarded_bodies=tuple(name(b) for b in GUARDED),
        finger_joints=(name("panda_finger_joint1"), name("panda_finger_joint2")),
        finger_bodies=(name(FINGERS[0]), name(FINGERS[1])),
        pads=(name("left_pad"), name("right_pad")),
        gripper_actuator=name("gripper"),
    )


PANDA = RobotDescription(
    name="panda",
    summary="two Franka Pandas (example-robot-data), fingers on 12 mm spacers",
    arms={"left": _arm("left"), "right": _arm("right")},
    finger_stroke=0.04,  # the real hand's 0-40 mm a finger
    finger_gains=(1.0, 1.0),
    closed_width=0.024,  # each finger on a 12 mm spacer: the stock hand closes to 0
    open_margin=0.002,
    grasp_height=0.012,  # at the centre the hand's underside is 6 mm above the brick's top
    clear_pose=(0.30, 0.62, 0.40),
    static_bodies=(),
)
