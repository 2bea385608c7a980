"""Judge a finished build against its targets and write the result document."""

from __future__ import annotations

import json
import math
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..core.poses import symmetric_yaw_error, tilt_of, yaw_of
from ..physics.loop import RawResult


@dataclass(frozen=True)
class Tolerances:
    """What counts as placed (issue 2): across the face and along x, height, yaw, tilt."""

    xy_mm: float = 5.0
    z_mm: float = 3.0
    yaw_deg: float = 3.0
    tilt_deg: float = 2.0


def quat_to_matrix(q: np.ndarray) -> np.ndarray:
    w, x, y, z = q / np.linalg.norm(q)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def brick_report(raw: RawResult, tol: Tolerances) -> list[dict[str, Any]]:
    """Per brick, in build order: target, final pose, errors and whether it is in place."""
    rows = []
    for b in raw.plan.bricks:
        target = b.target.pose
        row: dict[str, Any] = {
            "index": b.index,
            "arm": b.arm,
            "layer": b.target.layer,
            "target": {"position": [round(v, 6) for v in (target.x, target.y, target.z)], "yaw": round(target.yaw, 6)},
            "dropped": b.index in raw.dropped,
            "drops": sum(d.brick == b.index for d in raw.drops),
            "slip_mm": round(raw.slip_mm[b.index], 3) if b.index in raw.slip_mm else None,
        }
        slot = raw.slot_of.get(b.index)
        if slot is None or not np.all(np.isfinite(raw.final_pos[slot])):
            row.update(final=None, placed=False)
            rows.append(row)
            continue
        pos, quat = raw.final_pos[slot], raw.final_quat[slot]
        rot = quat_to_matrix(quat)
        err = pos - target.position
        row.update(
            final={"position": [round(float(v), 6) for v in pos], "quat": [round(float(v), 6) for v in quat]},
            error_xy_mm=round(float(np.hypot(err[0], err[1]) * 1000), 3),
            error_z_mm=round(float(err[2] * 1000), 3),
            yaw_error_deg=round(math.degrees(symmetric_yaw_error(yaw_of(rot), target.yaw)), 3),
            tilt_deg=round(math.degrees(tilt_of(rot)), 3),
        )
        row["knocked_off"] = any(k.slot == slot for k in raw.knocks)
        row["placed"] = (
            row["error_xy_mm"] <= tol.xy_mm
            and abs(row["error_z_mm"]) <= tol.z_mm
            and row["yaw_error_deg"] <= tol.yaw_deg
            and row["tilt_deg"] <= tol.tilt_deg
        )
        rows.append(row)
    return rows


def result_document(raw: RawResult, tol: Tolerances = Tolerances()) -> dict[str, Any]:
    """The `result.json` document of a build."""
    bricks = brick_report(raw, tol)
    placed = sum(b["placed"] for b in bricks)
    n = len(bricks)
    slips = [v for v in raw.slip_mm.values() if math.isfinite(v)]
    over_speed = raw.joint_speed_ratio > 1.0
    # A drop the build recovered from does not fail it: the structure is judged as it stands.
    success = raw.failure is None and placed == n and raw.arm_arm_contacts == 0 and not over_speed
    reason = raw.failure
    if reason is None and not success:
        missing = [b["index"] for b in bricks if not b["placed"]]
        problems = [f"{n - placed} of {n} bricks not in place (build order {missing})"] if missing else []
        if raw.dropped:
            problems.append(f"bricks dropped (build order {sorted(raw.dropped)})")
        if raw.knocks:
            problems.append(f"bricks knocked off (build order {[k.brick for k in raw.knocks]})")
        if raw.arm_arm_contacts:
            problems.append(f"{raw.arm_arm_contacts} arm-arm contacts")
        if over_speed:
            problems.append(f"a joint moved at {raw.joint_speed_ratio:.2f} of its velocity limit")
        reason = "; ".join(problems)
    errors = [b.get("error_xy_mm") for b in bricks]
    # None when a brick never reached the structure: result.json stays strict JSON (no Infinity).
    worst = None if None in errors else max(errors, default=0.0)
    return {
        "success": success,
        "failure_reason": reason,
        "structure": raw.plan.structure,
        "size": raw.plan.spec.size,
        "arms": raw.plan.arms,
        "bricks_total": n,
        "bricks_placed": placed,
        "bricks": bricks,
        "worst_error_xy_mm": worst,
        "sim_time_s": round(raw.sim_time, 3),
        "wall_time_s": round(raw.wall_time, 3),
        "real_time_factor": round(raw.sim_time / raw.wall_time, 3) if raw.wall_time > 0 else None,
        "sim_s_per_brick": round(raw.sim_time / n, 3) if n else None,
        "max_slip_mm": round(max(slips), 3) if slips else None,
        "drops": len(raw.drops),
        "recoveries": sum(
            any(b["index"] == d.brick and b["placed"] for b in bricks) for d in raw.drops
        ),
        "drop_events": [d.as_json() for d in raw.drops],
        "knocked_off": [k.as_json() for k in raw.knocks],
        "closest_arm_approach_mm": round(raw.closest_arm_m * 1000.0, 1),
        "closest_arm_approach_t_s": (
            round(raw.closest_arm_time, 3) if raw.closest_arm_time is not None else None
        ),
        "arm_arm_contacts": raw.arm_arm_contacts,
        "shared_zone_violations": raw.zone_violations,
        "finger_limit_excess_mm": round(raw.finger_limit_mm, 4),
        "max_joint_speed_ratio": round(raw.joint_speed_ratio, 4),
        "max_joint_torque_ratio": round(raw.joint_torque_ratio, 4),
        "mujoco_warnings": raw.warnings,
        "physics_steps": raw.physics_steps,
    }


def write_json_atomic(path: Path, document: dict[str, Any]) -> None:
    """Write to a temporary file beside `path`, then rename: never a half-written file."""
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
    os.chmod(tmp, 0o644)
    try:
        with os.fdopen(fd, "w") as f:
            json.dump(document, f, indent=2)
            f.write("\n")
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
