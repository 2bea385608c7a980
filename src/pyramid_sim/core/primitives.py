"""DE NIRO's motion primitives as lists of steps: pure, no MuJoCo.

pick  = hover, approach, servo, grip, retract (approach and retract at half the hover distance,
        as DE NIRO halves it for picking);
place = hover, servo, release, retract;
re-place = a pick where a brick let go off its target lies, and its place again;
clear = move to the arm's outer collision-clear pose.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from enum import Enum

from ..choices import Arm
from ..config import MotionConfig
from ..robots import RobotDescription
from .poses import Pose, grasp_yaw
from .trajectory import bounded_speed, turned_within
from .zone import Zone, segment_gap

# Grasps take the hand yaw nearest this one (of the two that grip a brick across its width).
YAW_REFERENCE = 0.0
# m/s^2: a quick lift's bound, what DE NIRO's own slow 5 cm moves reach (docs/performance.md)
LIFT_ACCELERATION = 2.0


class StepKind(str, Enum):
    MOVE = "move"
    GRIP = "grip"
    RELEASE = "release"


@dataclass(frozen=True)
class Step:
    """One primitive: a move of the tool centre to `pose`, or a gripper action."""

    name: str
    kind: StepKind
    pose: Pose | None = None
    speed: float = 0.0
    enters_zone: bool = False  # the first step into the shared zone waits for the barrier
    needs_brick: bool = False  # and, to pick, for a brick on the spawn spot
    transit: bool = False  # up, over and down at the higher end's height (trajectory.plan_path)


def pick_steps(
    brick: Pose,
    motion: MotionConfig,
    carry_to: Pose | None = None,
    *,
    grasp_height: float,
    yaw_ref: float = YAW_REFERENCE,
    then_yaw: float | None = None,
    quick_lift: bool = False,
    clearance: float = 0.0,
) -> list[Step]:
    """Steps that pick the brick resting at `brick`, gripping `grasp_height` above its centre
    (`clearance` off it towards the hand's fixed jaw, tool -y, for a one-jaw hand: the moving
    jaw then closes the brick onto the fixed one).

    With `carry_to` (the resting pose the brick is for) the retract lifts straight up to that
    place's hover height, so the carry over to it is level: a carried brick never cuts down
    across the courses already laid (walls run towards the spawn spot). With `then_yaw` (the
    hand's yaw on the move after) the retract begins that turn (see `turned_within`); with
    `quick_lift` it lifts at the free speed, its acceleration bounded (`lift_speed`)."""
    grasp = brick.moved(dz=grasp_height).with_yaw(grasp_yaw(brick.yaw, yaw_ref))
    if clearance:  # the tool's y in the world is (sin yaw, -cos yaw): Rz(yaw) Rx(pi)
        yaw = grasp.yaw
        grasp = grasp.moved(dx=-clearance * math.sin(yaw), dy=clearance * math.cos(yaw))
    half = motion.hover / 2
    retract = grasp.moved(dz=half)
    if carry_to is not None:
        retract = grasp.moved(dz=max(half, carry_to.z + motion.hover - brick.z))
    lift = lift_speed(retract.z - grasp.z, motion) if quick_lift else motion.slow_speed
    if then_yaw is not None:
        retract = turned_within(grasp, retract, then_yaw, lift, motion.turn_rate)
    return [
        # Back from a place above the courses: level over to the spot, then down.
        Step(
            "hover",
            StepKind.MOVE,
            grasp.moved(dz=motion.hover),
            motion.speed,
            enters_zone=True,
            transit=True,
            needs_brick=True,
        ),
        Step("approach", StepKind.MOVE, grasp.moved(dz=half), motion.slow_speed),
        Step("servo", StepKind.MOVE, grasp, motion.slow_speed),
        Step("grip", StepKind.GRIP),
        Step("retract", StepKind.MOVE, retract, lift),
    ]


def place_steps(
    target: Pose,
    motion: MotionConfig,
    *,
    grasp_height: float,
    yaw_ref: float = YAW_REFERENCE,
    then_yaw: float | None = None,
) -> list[Step]:
    """Steps that set a held brick down at `target` (its resting pose) and let go of it; with
    `then_yaw` the empty hand begins its turn to the next move on the way up."""
    hold = target.moved(dz=grasp_height).with_yaw(grasp_yaw(target.yaw, yaw_ref))
    release = hold.moved(dz=motion.release_clearance)
    up = hold.moved(dz=motion.hover)
    if then_yaw is not None:
        up = turned_within(release, up, then_yaw, motion.slow_speed, motion.turn_rate)
    return [
        Step("hover", StepKind.MOVE, hold.moved(dz=motion.hover), motion.speed, enters_zone=True),
        Step("servo", StepKind.MOVE, release, motion.slow_speed),
        Step("release", StepKind.RELEASE),
        Step("retract", StepKind.MOVE, up, motion.slow_speed),
    ]


def re_place_steps(
    lies: Pose,
    target: Pose,
    motion: MotionConfig,
    *,
    grasp_height: float,
    yaw_ref: float = YAW_REFERENCE,
    clearance: float = 0.0,
) -> list[Step]:
    """Steps that pick a brick let go off its target up again where it `lies` and set it
    down at `target`: a pick and a place, by an arm already in the shared zone (so no step
    waits at its edge, nor for the spawn spot)."""
    pick = pick_steps(
        lies, motion, target, grasp_height=grasp_height, yaw_ref=yaw_ref, clearance=clearance
    )
    place = place_steps(target, motion, grasp_height=grasp_height, yaw_ref=yaw_ref)
    first_pick = replace(pick[0], enters_zone=False, needs_brick=False)
    return [first_pick, *pick[1:], replace(place[0], enters_zone=False), *place[1:]]


def lift_speed(distance: float, motion: MotionConfig) -> float:
    """The peak speed of a quick lift over `distance`: the free speed, bounded by
    `LIFT_ACCELERATION`, never below the slow speed of DE NIRO's retract."""
    return max(motion.slow_speed, bounded_speed(distance, motion.speed, LIFT_ACCELERATION))


def clear_pose(arm: Arm, robot: RobotDescription) -> Pose:
    """The arm's outer collision-clear pose, out to its own side."""
    x, y, z = robot.clear_pose
    return Pose(x, y if arm == "left" else -y, z, robot.arms[arm].yaw_reference)


def standby_step(
    arm: Arm,
    zones: Sequence[Zone],
    x: float,
    at: Pose,
    motion: MotionConfig,
    clearance: float,
    bricks: Sequence[Pose] = (),
    reach: float = 0.0,
) -> Step:
    """A move to wait at `x`, just outside every zone across that line on the arm's own side,
    level with `at` (the pose the arm goes on to): the overlap schedule's waiting place. It is
    raised to hover over any of `bricks` within `reach` of the way on to `at` (a structure
    built round the spot), as the move on keeps its height until over `at`."""
    across = [z for z in zones if z.x_min <= x <= z.x_max]
    if arm == "left":
        y = max([z.y_max for z in across], default=at.y) + clearance
    else:
        y = min([z.y_min for z in across], default=at.y) - clearance
    z = max(
        [at.z]
        + [
            b.z + motion.hover
            for b in bricks
            if segment_gap((b.x, b.y), (b.x, b.y), (x, y), (at.x, at.y)) < reach
        ]
    )
    return Step("standby", StepKind.MOVE, Pose(x, y, z, at.yaw), motion.speed, transit=True)


def clear_steps(arm: Arm, motion: MotionConfig, robot: RobotDescription) -> list[Step]:
    return [Step("clear", StepKind.MOVE, clear_pose(arm, robot), motion.speed)]
