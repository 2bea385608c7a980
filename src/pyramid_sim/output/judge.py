"""Judge what a build measured against its targets: the `BuildResult`."""

from __future__ import annotations

import math
from dataclasses import asdict, replace
from typing import Any

import numpy as np

from ..choices import ARMS
from ..config import SimConfig
from ..core.measurements import Measurements
from ..core.plan import Plan
from ..core.poses import Pose, quat_to_matrix, symmetric_yaw_error, tilt_of, yaw_of
from .result import (
    BrickResult,
    BuildInputs,
    BuildResult,
    FinalPose,
    Target,
    Tolerances,
    versions,
)


def _round_all(values: object, digits: int) -> tuple[float, ...]:
    return tuple(round(float(v), digits) for v in values)  # type: ignore[attr-defined]


def judge_bricks(measured: Measurements, tol: Tolerances) -> tuple[BrickResult, ...]:
    """Per brick, in build order: target, final pose, errors and whether it is in place."""
    rows = []
    dropped = measured.dropped
    for b in measured.plan.bricks:
        pose = b.target.pose
        target = Target(_round_all((pose.x, pose.y, pose.z), 6), round(pose.yaw, 6))  # type: ignore[arg-type]
        slip = measured.slip_mm.get(b.index)
        common: dict[str, Any] = dict(
            index=b.index,
            arm=b.arm,
            layer=b.target.layer,
            target=target,
            dropped=b.index in dropped,
            drops=sum(d.brick == b.index for d in measured.drops),
            slip_mm=round(slip, 3) if slip is not None else None,
        )
        slot = measured.slot_of.get(b.index)
        if slot is None or not np.all(np.isfinite(measured.final_pos[slot])):
            rows.append(
                BrickResult(
                    **common,
                    final=None,
                    error_xy_mm=None,
                    error_z_mm=None,
                    yaw_error_deg=None,
                    tilt_deg=None,
                    knocked_off=False,
                    placed=False,
                )
            )
            continue
        pos, quat = measured.final_pos[slot], measured.final_quat[slot]
        xy, z, yaw, tilt = (round(e, 3) for e in placement_errors(pos, quat, pose))
        rows.append(
            BrickResult(
                **common,
                final=FinalPose(_round_all(pos, 6), _round_all(quat, 6)),  # type: ignore[arg-type]
                error_xy_mm=xy,
                error_z_mm=z,
                yaw_error_deg=yaw,
                tilt_deg=tilt,
                knocked_off=any(k.slot == slot for k in measured.knocks),
                placed=within(tol, xy, z, yaw, tilt),
            )
        )
    return tuple(rows)


def placement_errors(
    position: np.ndarray, quat: np.ndarray, target: Pose
) -> tuple[float, float, float, float]:
    """How far a brick lies from its target: across (mm), in height (mm, signed), in yaw
    (degrees, a brick turned half round lies the same) and its tilt (degrees)."""
    rot = quat_to_matrix(quat)
    err = position - target.position
    return (
        float(np.hypot(err[0], err[1]) * 1000),
        float(err[2] * 1000),
        math.degrees(symmetric_yaw_error(yaw_of(rot), target.yaw)),
        math.degrees(tilt_of(rot)),
    )


def within(tol: Tolerances, xy_mm: float, z_mm: float, yaw_deg: float, tilt_deg: float) -> bool:
    """A brick with these errors is in place."""
    return (
        xy_mm <= tol.xy_mm
        and abs(z_mm) <= tol.z_mm
        and yaw_deg <= tol.yaw_deg
        and tilt_deg <= tol.tilt_deg
    )


FINGER_GIVE_MM = 0.1  # a finger joint's soft limit gives this much under the squeeze
IDLE_MOTION_LIMIT_MM = 1.0  # a brick nobody touched has moved: something threw it


def checks(
    measured: Measurements, bricks: tuple[BrickResult, ...], config: SimConfig
) -> dict[str, bool]:
    """Each condition of a successful build, True where it holds."""
    slips = [v for v in measured.slip_mm.values() if math.isfinite(v)]
    return {
        "finished": measured.failure is None,
        "bricks_in_place": all(b.placed for b in bricks),
        "slip": max(slips, default=0.0) <= config.slip_limit_mm,
        "arm_arm_contacts": measured.arm_arm_contacts == 0,
        "arm_body_contacts": measured.arm_body_contacts == 0,
        "shared_zone": measured.zone_violations == 0,
        "joint_speed": measured.joint_speed_ratio <= 1.0,
        "joint_torque": measured.joint_torque_ratio <= 1.0,
        "finger_range": measured.finger_limit_mm <= FINGER_GIVE_MM,
        "idle_bricks": measured.idle_motion_mm <= IDLE_MOTION_LIMIT_MM,
    }


def failure_reason(
    measured: Measurements,
    bricks: tuple[BrickResult, ...],
    held: dict[str, bool],
    config: SimConfig,
) -> str | None:
    """Why the build failed, or None: the loop's own reason first, else every check that
    failed. A drop the build recovered from does not fail it: the structure is judged as it
    stands."""
    if measured.failure is not None:
        return measured.failure
    if all(held.values()):
        return None
    n = len(bricks)
    missing = [b.index for b in bricks if not b.placed]
    problems = (
        [f"{len(missing)} of {n} bricks not in place (build order {missing})"] if missing else []
    )
    if missing and measured.dropped:
        problems.append(f"bricks dropped (build order {sorted(measured.dropped)})")
    if missing and measured.knocks:
        problems.append(f"bricks knocked off (build order {[k.brick for k in measured.knocks]})")
    slips = [v for v in measured.slip_mm.values() if math.isfinite(v)]
    texts = {
        "slip": f"a brick slid {max(slips, default=0.0):.1f} mm in the hand, over the "
        f"{config.slip_limit_mm:g} mm limit",
        "arm_arm_contacts": f"{measured.arm_arm_contacts} arm-arm contacts",
        "arm_body_contacts": f"{measured.arm_body_contacts} contacts of an arm with the robot's body",
        "shared_zone": f"both arms in one zone at {measured.zone_violations} control steps",
        "joint_speed": f"{joint_name(config, measured.speed_joint)} moved at "
        f"{measured.joint_speed_ratio:.2f} of its velocity limit "
        f"({joint_limit(config, measured.speed_joint, 'velocity'):g} rad/s)",
        "joint_torque": f"{joint_name(config, measured.torque_joint)} demanded "
        f"{measured.joint_torque_ratio:.2f} of its torque limit "
        f"({joint_limit(config, measured.torque_joint, 'torque'):g} N m, servo "
        "and gravity compensation)",
        "finger_range": f"a finger went {measured.finger_limit_mm:.2f} mm past its joint range",
        "idle_bricks": f"a brick nobody had touched moved {measured.idle_motion_mm:.1f} mm",
    }
    problems += [text for name, text in texts.items() if not held[name]]
    return "; ".join(problems)


def joint_name(config: SimConfig, joint: int | None) -> str:
    """`joint`, an arm joint counted across both arms (left first), as "the left arm's joint
    s1"; "a joint" when unknown."""
    if joint is None:
        return "a joint"
    arm, k = _arm_joint(config, joint)
    return (
        f"the {arm} arm's joint {config.robot_description.arms[arm].joints[k].rsplit('/', 1)[-1]}"
    )


def joint_limit(config: SimConfig, joint: int | None, kind: str) -> float:
    """The real arm's `kind` ("velocity" or "torque") limit of `joint`; NaN when unknown."""
    if joint is None:
        return math.nan
    arm, k = _arm_joint(config, joint)
    return getattr(config.robot_description.arms[arm], f"{kind}_limits")[k]


def _arm_joint(config: SimConfig, joint: int) -> tuple[str, int]:
    n = len(config.robot_description.arms[ARMS[0]].joints)
    return ARMS[joint // n], joint % n


def inputs_of(plan: Plan, config: SimConfig) -> BuildInputs:
    spec = plan.spec
    return BuildInputs(
        structure=spec.name,
        size=dict(spec.size),
        arms=plan.arms,
        seed=config.seed,
        goals_file=spec.goals_source or None,
        settings=asdict(replace(config, motion=config.hand_motion)),  # the speeds moved by
    )


def judge(measured: Measurements, config: SimConfig, tol: Tolerances = Tolerances()) -> BuildResult:
    """The `BuildResult` of a build: every brick judged, the run's figures rounded as written."""
    bricks = judge_bricks(measured, tol)
    n = len(bricks)
    slips = [v for v in measured.slip_mm.values() if math.isfinite(v)]
    errors = [b.error_xy_mm for b in bricks]
    held = checks(measured, bricks, config)
    reason = failure_reason(measured, bricks, held, config)
    wall = measured.wall_time
    return BuildResult(
        success=reason is None,
        failure_reason=reason,
        checks=held,
        failed_checks=tuple(name for name, ok in held.items() if not ok),
        robot=config.robot,
        structure=measured.plan.structure,
        size=dict(measured.plan.spec.size),
        arms=measured.plan.arms,
        bricks_total=n,
        bricks_placed=sum(b.placed for b in bricks),
        bricks=bricks,
        worst_error_xy_mm=None if None in errors else max(errors, default=0.0),  # type: ignore[type-var]
        sim_time_s=round(measured.sim_time, 3),
        wall_time_s=round(wall, 3),
        real_time_factor=round(measured.sim_time / wall, 3) if wall > 0 else None,
        sim_s_per_brick=round(measured.sim_time / n, 3) if n else None,
        max_slip_mm=round(max(slips), 3) if slips else None,
        slip_limit_mm=config.slip_limit_mm,
        drops=len(measured.drops),
        recoveries=sum(
            any(b.index == d.brick and b.placed for b in bricks) for d in measured.drops
        ),
        drop_events=tuple(measured.drops),
        knocked_off=tuple(measured.knocks),
        closest_arm_approach_mm=(  # None when the build stopped before the first look
            round(measured.closest_arm_m * 1000.0, 1)
            if math.isfinite(measured.closest_arm_m)
            else None
        ),
        closest_arm_approach_t_s=(
            round(measured.closest_arm_time, 3) if measured.closest_arm_time is not None else None
        ),
        arm_arm_contacts=measured.arm_arm_contacts,
        arm_body_contacts=measured.arm_body_contacts,
        shared_zone_violations=measured.zone_violations,
        finger_limit_excess_mm=round(measured.finger_limit_mm, 4),
        max_joint_speed_ratio=round(measured.joint_speed_ratio, 4),
        max_joint_torque_ratio=round(measured.joint_torque_ratio, 4),
        max_idle_brick_motion_mm=round(measured.idle_motion_mm, 3),
        contact_friction={k: round(v, 6) for k, v in measured.contact_friction.items()},
        mujoco_warnings=dict(measured.warnings),
        physics_steps=measured.physics_steps,
        ik_solves=measured.ik_solves,
        inputs=inputs_of(measured.plan, config),
        versions=versions(),
    )
