"""Frozen configuration values, each checked once where it is made.

Every entry point builds these, so a bad value is caught in one place and reported as one line
naming the field and its accepted range (ConfigError).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import Any

from .choices import CAMERAS, SCHEDULES, Camera, RobotName, Schedule, in_words
from .errors import ConfigError
from .params import Bound, check_range, check_section, default
from .robots import DEFAULT_ROBOT, RobotDescription, robot

Vec3 = tuple[float, float, float]
DROP_DISTANCE = 0.03  # m: a held brick this far from where it was gripped has left the hand
DROP_MM = DROP_DISTANCE * 1000.0  # so a slip is measured only short of it

# Ranges the command line's help states too: each is held here and read by both.
SPAWN_JITTER_MM = Bound("spawn jitter (mm)", 0.0, 10.0)
VIDEO_FPS = Bound("fps", 1, 120)
VIDEO_WIDTH = Bound("video width", 16, 1920)
VIDEO_HEIGHT = Bound("video height", 16, 1080)
SPEEDUP = Bound("speedup", 0.1, 100.0)
ANTIALIAS_SAMPLES = (0, 2, 4, 8)


def check_count(name: str, value: int, low: int, high: int) -> None:
    """Raise ConfigError unless `value` is a whole number from low to high."""
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        raise ConfigError(
            f"{name}: {value!r} is out of range; accepted {low} to {high}, whole numbers"
        )


@dataclass(frozen=True)
class BrickConfig:
    """The seed's brick: 0.192 x 0.086 x 0.062 m, long axis along its x, 0.5 kg."""

    length: float = 0.192
    width: float = 0.086
    height: float = 0.062
    mass: float = default("brick", "mass")
    friction: float = default("brick", "friction")  # of the brick geoms

    def __post_init__(self) -> None:
        check_range("brick length", self.length, 0.02, 0.5, low_open=True)
        check_range("brick width", self.width, 0.01, 0.095)
        check_range("brick height", self.height, 0.01, 0.2)
        check_section("brick", self)

    @property
    def size(self) -> Vec3:
        return (self.length, self.width, self.height)


@dataclass(frozen=True)
class GripperConfig:
    """Squeeze force, pad friction and how the fingers move (their travel and width are the
    robot's: `robots/`)."""

    force: float = default("gripper", "force")  # N, squeeze of each pad on the brick
    pad_friction: float = default("gripper", "pad_friction")
    close_time: float = 0.35  # s, the command ramp: a step slams the light fingers through
    settle_time: float = 0.15  # s after a grip's ramp, for the force to build
    stiffness: float = 2000.0  # N/m of finger-gap error: stiff, so the force limit sets the squeeze

    def __post_init__(self) -> None:
        check_section("gripper", self)
        check_range("gripper close time", self.close_time, 0.02, 2.0)
        check_range("gripper settle time", self.settle_time, 0.0, 2.0)
        check_range("gripper stiffness", self.stiffness, 100.0, 1e5)


@dataclass(frozen=True)
class LayoutConfig:
    """Where things stand: the table and the spawn spot (the robot's bases are its preset's).

    The world frame is the seed's robot frame: x forward, y to the left, z up, with the robot's
    base at z = 0 and the table top at 0.079 m so the seed's brick centre height 0.11 m rests
    on it.
    """

    table_top_z: float = 0.079
    spawn_xy: tuple[float, float] = (0.49, 0.01)
    spawn_yaw: float = math.pi / 2  # the seed turns the spawned brick 90 degrees
    spawn_jitter_mm: float = 0.0  # each spawned brick lands up to this far off the spot in x and y
    # The structure moved from where its generator lays it: shifted (m, x and y) and turned
    # (rad) about its footprint's centre. The learning variation draws these per episode.
    structure_shift: tuple[float, float] = (0.0, 0.0)
    structure_turn: float = 0.0
    brick_gap: float = 0.03  # m between neighbouring bricks across the face (DE NIRO's)
    structure_gap: float = 0.05  # m from the spot's brick to the structure (DE NIRO's)

    def __post_init__(self) -> None:
        check_range("table top z", self.table_top_z, 0.0, 0.3)
        check_range("structure shift x", self.structure_shift[0], -0.2, 0.2)
        check_range("structure shift y", self.structure_shift[1], -0.2, 0.2)
        check_range("structure turn", self.structure_turn, -math.pi / 2, math.pi / 2)
        SPAWN_JITTER_MM.check(self.spawn_jitter_mm)
        check_range("spawn yaw", self.spawn_yaw, -math.pi, math.pi)
        check_range("spawn x", self.spawn_xy[0], 0.3, 0.8)
        check_range("spawn y", self.spawn_xy[1], -0.4, 0.4)
        check_range("brick gap", self.brick_gap, 0.0, 0.1)
        check_range("structure gap", self.structure_gap, 0.0, 0.2)


@dataclass(frozen=True)
class MotionConfig:
    """Primitive distances and speeds (the seed's hover distance 0.1 m, halved to pick)."""

    hover: float = 0.10  # m above a place target; picks hover at half of it, as the seed
    release_clearance: float = 0.004  # m above the resting pose where a brick is let go
    speed: float = 0.6  # m/s, peak Cartesian speed of free moves
    slow_speed: float = 0.25  # m/s, servo moves near bricks
    turn_rate: float = 1.5  # rad/s, peak hand rotation rate
    control_dt: float = 0.01  # s, IK rate (100 Hz)
    settle_before_release: float = 0.15  # s held still at the release pose
    position_tolerance: float = 0.002  # m, IK target reached
    arm_min_distance: float = 0.05  # m the IK keeps between the arms' links (beyond the lockstep)
    free_ik_interval: int = 1  # control steps per IK solve in free motion (up to 4; see docs)

    def __post_init__(self) -> None:
        check_range("hover distance", self.hover, 0.02, 0.3)
        check_range("release clearance", self.release_clearance, 0.0, 0.05)
        check_range("speed", self.speed, 0.0, 1.5, low_open=True)
        check_range("slow speed", self.slow_speed, 0.0, 1.0, low_open=True)
        check_range("turn rate", self.turn_rate, 0.0, 6.0, low_open=True)
        check_range("control dt", self.control_dt, 0.002, 0.05)
        check_range("settle before release", self.settle_before_release, 0.0, 2.0)
        check_range("arm min distance", self.arm_min_distance, 0.0, 0.3)
        check_count("free IK interval", self.free_ik_interval, 1, 4)


@dataclass(frozen=True)
class SimConfig:
    """Everything a build needs beyond the structure itself."""

    robot: RobotName = DEFAULT_ROBOT  # a preset of robots/
    schedule: Schedule = "lockstep"  # the seed's four phases, or "overlap" (core/overlap.py)
    brick: BrickConfig = field(default_factory=BrickConfig)
    gripper: GripperConfig = field(default_factory=GripperConfig)
    layout: LayoutConfig = field(default_factory=LayoutConfig)
    motion: MotionConfig = field(default_factory=MotionConfig)
    timestep: float = 0.002
    settle_time: float = 1.0  # s of physics after both arms retract, before measuring
    max_sim_time: float = 600.0  # s, a build still running then has failed
    stall_time: float = 60.0  # s, a build in which no arm finishes a move for this long has failed
    seed: int = 0  # of the spawn jitter: the only randomness in a build
    spare_bricks: int = 3  # in the magazine beyond the structure's, to replace dropped ones
    slip_limit_mm: float = 5.0  # a brick that slid further in the hand fails the build

    def __post_init__(self) -> None:
        robot(self.robot)  # refuses an unknown preset, naming those there are
        if self.schedule not in SCHEDULES:
            raise ConfigError(
                f"schedule: unknown {self.schedule!r}; accepted {', '.join(SCHEDULES)}"
            )
        check_range("timestep", self.timestep, 0.0005, 0.004)
        check_range("settle time", self.settle_time, 0.0, 10.0)
        check_range("max sim time", self.max_sim_time, 1.0, 36000.0)
        check_range("stall time", self.stall_time, 1.0, 36000.0)
        check_count("seed", self.seed, 0, 2**32 - 1)
        check_count("spare bricks", self.spare_bricks, 0, 20)
        v = self.slip_limit_mm
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not 0.0 < v < DROP_MM:
            # a slip that far is a drop, so no slip is ever measured past it
            raise ConfigError(
                f"slip limit (mm): {v!r} is out of range; accepted (0, {DROP_MM:g}): a brick "
                f"{DROP_MM:g} mm out of its grip has been dropped"
            )
        steps = self.motion.control_dt / self.timestep
        if abs(steps - round(steps)) > 1e-9:
            raise ConfigError(
                f"control dt: {self.motion.control_dt} is not a whole number of timesteps "
                f"({self.timestep})"
            )

    @classmethod
    def for_robot(cls, name: str, **fields: Any) -> SimConfig:
        """The settings of robot preset `name` at its own scale: its brick, table, spawn
        spot, distances and grip (`scale` in robots/), with `fields` over them."""
        preset = robot(name)
        sections = {
            "brick": BrickConfig,
            "gripper": GripperConfig,
            "layout": LayoutConfig,
            "motion": MotionConfig,
        }
        scaled = {k: sections[k](**preset.scale[k]) for k in sections if k in preset.scale}
        return cls(robot=name, **{**scaled, **fields})  # type: ignore[arg-type]

    @cached_property
    def hand_motion(self) -> MotionConfig:
        """The motion settings the robot's hand moves by: `motion` with each speed capped at
        the robot's own limit (Baxter's wrist cannot turn its hand as fast as a Panda's). The
        cap is taken from the robot at hand, so changing the robot changes it; result.json
        records these."""
        preset, m = robot(self.robot), self.motion
        return replace(
            m,
            speed=min(m.speed, preset.max_speed),
            slow_speed=min(m.slow_speed, preset.max_slow_speed),
            turn_rate=min(m.turn_rate, preset.max_turn_rate),
        )

    @property
    def robot_description(self) -> RobotDescription:
        """The description of the robot this build runs (`robots/`)."""
        return robot(self.robot)

    @property
    def substeps(self) -> int:
        """Physics steps per control step."""
        return int(round(self.motion.control_dt / self.timestep))


@dataclass(frozen=True)
class VideoConfig:
    """What to render: frame rate, size, camera, shadows and multisample anti-aliasing.

    Both extras are off by default: on the CPU (llvmpipe) 4x MSAA costs ~1.7x and shadows ~4x
    the frame time, and the default video must render faster than the build it shows.
    """

    fps: int = 30
    width: int = 640
    height: int = 480
    camera: Camera = "overview"
    shadows: bool = False
    antialias: int = 0
    speedup: float = 1.0  # simulated seconds shown per second of video

    def __post_init__(self) -> None:
        VIDEO_FPS.check(self.fps)
        VIDEO_WIDTH.check(self.width)
        VIDEO_HEIGHT.check(self.height)
        SPEEDUP.check(self.speedup)
        if self.antialias not in ANTIALIAS_SAMPLES:
            raise ConfigError(f"antialias: {self.antialias} samples; accepted {antialias_text()}")
        if self.width % 2 or self.height % 2:
            raise ConfigError(
                f"video size: {self.width}x{self.height} must be even in both (H.264); "
                f"accepted width {VIDEO_WIDTH.text}, height {VIDEO_HEIGHT.text}"
            )
        if self.camera not in CAMERAS:
            raise ConfigError(f"camera: unknown {self.camera!r}; accepted {', '.join(CAMERAS)}")

    @property
    def frame_dt(self) -> float:
        """Simulated seconds between two frames: one frame every speedup / fps."""
        return self.speedup / self.fps


def antialias_text() -> str:
    """The accepted sample counts as a person reads them: `0, 2, 4 or 8`."""
    return in_words(ANTIALIAS_SAMPLES)


def check_film(video: VideoConfig, config: SimConfig) -> None:
    """ConfigError unless the video's frames are at least a physics step apart: the loop
    films at most one frame a step, so a slower motion could not be honoured."""
    slowest = video.fps * config.timestep
    if video.frame_dt < config.timestep - 1e-12:
        raise ConfigError(
            f"speedup: {video.speedup:g} at {video.fps} fps asks a frame every "
            f"{video.frame_dt * 1000:.2g} ms of simulated time, less than the "
            f"{config.timestep * 1000:g} ms physics step; accepted {slowest:.3g} to "
            f"{SPEEDUP.high:g} at "
            f"{video.fps} fps"
        )
