"""Names used in the MuJoCo scene, spelled once."""

from typing import Final

ARMS: Final = ("left", "right")

ARM_JOINTS: Final = tuple(f"panda_joint{i}" for i in range(1, 8))
FINGER_JOINTS: Final = ("panda_finger_joint1", "panda_finger_joint2")
TCP_SITE: Final = "tcp"
HAND_BODY: Final = "panda_hand"
FINGER_BODIES: Final = ("panda_leftfinger", "panda_rightfinger")
# The links whose positions tell whether an arm is inside the shared zone.
ZONE_BODIES: Final = (HAND_BODY, "panda_link6", "panda_link4")
# The links that can meet the other arm over the table, from the elbow out: the IK keeps them
# apart. The bases stand 0.5 m apart, and the base and shoulder links turn about their own spot.
IK_GUARDED_BODIES: Final = (
    "panda_link3", "panda_link4", "panda_link5", "panda_link6", "panda_link7", HAND_BODY,
)
PAD_GEOMS: Final = ("left_pad", "right_pad")
GRIPPER_ACTUATOR: Final = "gripper"
GRIPPER_TENDON: Final = "finger_gap"

# The real Panda's limits (Franka datasheet, also in example-robot-data's URDF).
JOINT_VELOCITY_LIMITS: Final = (2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61)
JOINT_TORQUE_LIMITS: Final = (87.0, 87.0, 87.0, 87.0, 12.0, 12.0, 12.0)
JOINT_ACCELERATION_LIMITS: Final = (15.0, 7.5, 10.0, 12.5, 15.0, 20.0, 20.0)
# Joint damping (N m s/rad): 10 on the big joints (at 1 or 4, walls built by two arms lost
# bricks); 2 on the wrist, whose 12 N m cannot turn the hand at the IK's speed against 10.
JOINT_DAMPING: Final = (10.0, 10.0, 10.0, 10.0, 2.0, 2.0, 2.0)
# Position gains from shoulder to wrist (FINDINGS.md).
JOINT_KP: Final = (4500.0, 4500.0, 3500.0, 3500.0, 2000.0, 2000.0, 2000.0)

# A comfortable arm posture with the hand pointing down in front of the robot.
HOME_QPOS: Final = (0.0, -0.3, 0.0, -2.2, 0.0, 1.9, 0.785)

ARM_ROOT_BODY: Final = "panda_link0"
ARM_ARM_SENSOR: Final = "arm_arm_contacts"  # contacts between the two arms, counted by MuJoCo

BRICK_PREFIX: Final = "brick"
TABLE_GEOM: Final = "table_top"
SPAWN_VOLUME: Final = "spawn_volume"  # a brick's box at the spawn spot, grown by the jitter


def prefixed(arm: str, name: str) -> str:
    """Scene name of a robot element: robots are attached with the prefix `arm/`."""
    return f"{arm}/{name}"


def brick_name(index: int) -> str:
    """Prefix of the brick with magazine slot `index`."""
    return f"{BRICK_PREFIX}{index:02d}/"
