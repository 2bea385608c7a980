"""The result of a build: one typed, immutable `BuildResult` with its bricks, and its one
serialisation: `to_dict` (the document), `to_json` (its text, as `result.json` holds it) and
`save` (that file, written atomically).

Values are kept as written to result.json (rounded), so a field read in Python and the same
field read from the file agree. Pure: no MuJoCo.
"""

from __future__ import annotations

import importlib.metadata
import json
import platform
from dataclasses import asdict, dataclass
from functools import lru_cache
from pathlib import Path
from typing import Any

from ..choices import Arm
from ..core.incidents import Drop, Knock
from .files import write_atomic

Vec3 = tuple[float, float, float]


@dataclass(frozen=True)
class Tolerances:
    """What counts as placed: across the face and along x, height, yaw, tilt."""

    xy_mm: float = 5.0
    z_mm: float = 3.0
    yaw_deg: float = 3.0
    tilt_deg: float = 2.0


@dataclass(frozen=True)
class Target:
    """Where a brick must rest: position (m) and yaw (rad)."""

    position: Vec3
    yaw: float


@dataclass(frozen=True)
class FinalPose:
    """Where a brick came to rest: position (m) and quaternion (w, x, y, z)."""

    position: Vec3
    quat: tuple[float, float, float, float]


@dataclass(frozen=True)
class BrickResult:
    """One brick of the structure, in build order. The errors are None when no brick reached
    the structure for this place (never picked, or its state not finite)."""

    index: int
    arm: Arm
    layer: int
    target: Target
    dropped: bool
    drops: int
    slip_mm: float | None
    final: FinalPose | None
    error_xy_mm: float | None
    error_z_mm: float | None
    yaw_error_deg: float | None
    tilt_deg: float | None
    knocked_off: bool
    placed: bool

    def to_dict(self) -> dict[str, Any]:
        doc = asdict(self)
        doc["target"] = {"position": list(self.target.position), "yaw": self.target.yaw}
        if self.final is not None:
            doc["final"] = {"position": list(self.final.position), "quat": list(self.final.quat)}
        return doc


@dataclass(frozen=True)
class BuildInputs:
    """Everything a build was made from, so a result file alone says how to reproduce it."""

    structure: str
    size: dict[str, int]
    arms: str
    seed: int
    goals_file: str | None
    settings: dict[str, Any]  # the whole SimConfig, as nested dicts

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


@dataclass(frozen=True)
class VideoInfo:
    path: str
    frames: int
    fps: int
    speedup: float = 1.0  # simulated seconds a second of video


@dataclass(frozen=True)
class BuildResult:
    """A finished (or stopped) build: the judgement, every brick, and what the loop measured."""

    success: bool
    failure_reason: str | None
    checks: dict[str, bool]  # each condition of success, True where it held
    failed_checks: tuple[str, ...]
    robot: str  # the preset that built it
    structure: str
    size: dict[str, int]
    arms: str
    bricks_total: int
    bricks_placed: int
    bricks: tuple[BrickResult, ...]
    worst_error_xy_mm: float | None  # None when some brick never reached the structure
    sim_time_s: float
    wall_time_s: float
    real_time_factor: float | None
    sim_s_per_brick: float | None
    max_slip_mm: float | None
    slip_limit_mm: float
    drops: int
    recoveries: int
    drop_events: tuple[Drop, ...]
    knocked_off: tuple[Knock, ...]
    closest_arm_approach_mm: float | None  # None if the arms were never measured
    closest_arm_approach_t_s: float | None
    arm_arm_contacts: int
    arm_body_contacts: int  # an arm against its own robot's body (torso, head)
    shared_zone_violations: int
    finger_limit_excess_mm: float
    max_joint_speed_ratio: float
    max_joint_torque_ratio: float  # demanded (servo + gravity compensation) over the limit
    max_idle_brick_motion_mm: float  # the furthest a brick moved before an arm reached for it
    contact_friction: dict[str, float]  # brick_brick, brick_table, pad_brick, from the model
    mujoco_warnings: dict[str, int]
    physics_steps: int
    ik_solves: int  # control steps that solved the IK; the rest followed a solve's plan
    inputs: BuildInputs
    versions: dict[str, str]
    video: VideoInfo | None = None

    def to_json(self) -> str:
        """The text of `result.json`, exactly as the command line writes it."""
        return json.dumps(self.to_dict(), indent=2, allow_nan=False) + "\n"

    def save(self, path: str | Path) -> None:
        """Write `to_json()` to `path` whole or not at all (as `pyramid-sim build` writes
        DIR/result.json)."""
        text = self.to_json()
        write_atomic(Path(path), lambda tmp: tmp.write_text(text))

    def to_dict(self) -> dict[str, Any]:
        """The `result.json` document as a dict, as `json.load` reads the file (strict JSON: no
        NaN or Infinity)."""
        doc: dict[str, Any] = {}
        for name in self.__dataclass_fields__:
            value = getattr(self, name)
            if name == "bricks":
                value = [b.to_dict() for b in value]
            elif name in ("drop_events", "knocked_off"):
                value = [e.to_dict() for e in value]
            elif name == "failed_checks":
                value = list(value)
            elif name in ("inputs", "video"):
                if value is None:
                    continue
                value = asdict(value)
            doc[name] = value
        return json.loads(json.dumps(doc, allow_nan=False))  # tuples as lists, as the file reads


@lru_cache(maxsize=1)
def versions() -> dict[str, str]:
    """The versions that produce a result: pyramid_sim, the physics and IK, numpy, Python."""
    found = {"python": platform.python_version()}
    for name in ("pyramid_sim", "mujoco", "mink", "numpy"):
        try:
            found[name] = importlib.metadata.version(name)
        except importlib.metadata.PackageNotFoundError:
            found[name] = "unknown"
    return found
