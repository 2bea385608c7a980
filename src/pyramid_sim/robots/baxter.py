"""Rethink Baxter, DE NIRO's own robot: one torso, two 7-joint arms and electric parallel
grippers, in its own base frame (DE NIRO's coordinates are in it). Every Baxter name, limit
and dimension lives here and in physics/robot_models/baxter.py."""

from __future__ import annotations

from .description import ArmDescription, RobotDescription

JOINTS = ("s0", "s1", "e0", "e1", "w0", "w1", "w2")
# baxter.urdf's limits: 50 N m and 1.5 rad/s shoulder to elbow, 15 N m and 4 rad/s the wrist.
VELOCITY_LIMITS = (1.5, 1.5, 1.5, 1.5, 4.0, 4.0, 4.0)
TORQUE_LIMITS = (50.0, 50.0, 50.0, 50.0, 15.0, 15.0, 15.0)
ACCELERATION_LIMITS = (4.0, 4.0, 4.0, 4.0, 8.0, 8.0, 8.0)  # not in the URDF: kept modest
KP = (3000.0, 3000.0, 2000.0, 2000.0, 800.0, 800.0, 800.0)  # FINDINGS.md: these held
DAMPING = (20.0, 20.0, 10.0, 10.0, 2.0, 2.0, 2.0)
# Rethink's "untucked" posture (baxter_tools' tuck_arms.py), mirrored for the right arm.
HOME = {
    "left": (-0.08, -1.0, -1.19, 1.94, 0.67, 1.03, -0.50),
    "right": (0.08, -1.0, 1.19, 1.94, -0.67, 1.03, 0.50),
}
# The hand's yaw at home: its x axis points back towards the robot (w2 then mid-range).
YAW_REFERENCE = {"left": 2.86, "right": -2.86}
MOUNTS = {"left": (0.025, 0.22, 0.119), "right": (0.025, -0.22, 0.119)}
# From the elbow out; the upper elbow turns about the shoulder, 11 mm from the torso at home.
GUARDED = (
    "upper_elbow_visual",
    "lower_elbow",
    "upper_forearm",
    "upper_forearm_visual",
    "lower_forearm",
    "wrist",
    "hand_link",
    "gripper_base_link",
)
FINGER_STROKE = 0.020833  # m each finger slides: the real gripper's
SLOT_4_CLOSED = 0.054  # m between the paddle tips closed, fingers in slot 4 (of the xacro's 1-4)


PREFIX = "baxter/"  # the robot is attached to the scene under this prefix


def _arm(side: str) -> ArmDescription:
    g = PREFIX + side[0]  # the gripper's links are named "l_gripper_..." and "r_gripper_..."
    s = PREFIX + side
    return ArmDescription(
        joints=tuple(f"{s}_{j}" for j in JOINTS),
        velocity_limits=VELOCITY_LIMITS,
        torque_limits=TORQUE_LIMITS,
        acceleration_limits=ACCELERATION_LIMITS,
        kp=KP,
        damping=DAMPING,
        home=HOME[side],
        base=MOUNTS[side],
        root_body=f"{s}_arm_mount",
        tcp_site=f"{s}_tcp",
        zone_bodies=(f"{s}_gripper_base_link", f"{s}_wrist", f"{s}_lower_elbow"),
        guarded_bodies=tuple(f"{s}_{b}" for b in GUARDED),
        finger_joints=(f"{g}_gripper_l_finger_joint", f"{g}_gripper_r_finger_joint"),
        finger_bodies=(f"{g}_gripper_l_finger_tip", f"{g}_gripper_r_finger_tip"),
        pads=(f"{s}_pad_l", f"{s}_pad_r"),
        gripper_actuator=f"{s}_gripper",
        yaw_reference=YAW_REFERENCE[side],
    )


BAXTER = RobotDescription(
    name="baxter",
    summary="Rethink Baxter (example-robot-data), electric grippers in slot 4, paddle tips",
    arms={"left": _arm("left"), "right": _arm("right")},
    finger_stroke=FINGER_STROKE,
    finger_gains=(1.0, -1.0),  # the left finger opens with rising travel, the right falling
    closed_width=SLOT_4_CLOSED,
    open_margin=0.0003,  # of 20.8 mm: the open pads clear the brick by 4.5 mm a side
    grasp_height=0.005,
    posture_cost=1e-3,  # at 1e-2 the long arms settled 1.0-1.4 mm short of a target
    # Half the Panda's speeds (FINDINGS.md: picks and places held at 0.3 m/s): the 15 N m
    # wrist could not keep the hand's yaw at the Panda's pace.
    max_speed=0.3,
    max_slow_speed=0.15,
    max_turn_rate=0.75,
    # The hand modes, slower to speed up and to stop: its shoulder s1 holds the arm and a
    # brick at up to 0.9 of its 50 N m where the layouts reach, and the motion generator,
    # lagging the IK by a few cm, braked at 2 rad/s^2 (about 8 N m on the outstretched arm):
    # the expert's waypoints failed on torque, 1.01-1.09 (docs/notes/2026-11-28-baxter-holding.md).
    # A waypoint's
    # speed is taken up and dropped at 0.5 m/s^2 (the build's minimum-jerk moves peak near
    # it), and the generator accelerates the joints at a quarter of their limits.
    hand_acceleration=0.5,
    hand_modes_acceleration_share=0.25,
    clear_pose=(0.45, 0.60, 0.30),
    static_bodies=tuple(
        PREFIX + b for b in ("torso", "pedestal", "collision_head_link_1", "collision_head_link_2")
    ),
)
