"""A sweep's grid: which parameters vary, over which values, and one SweepRun per run.

Pure (no MuJoCo): parsing `start:stop:count` or comma lists, checking every value through the
configuration classes, and naming each run by the text of its parameters so a re-run can tell
which runs are already in the CSV.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

from ..choices import ARM_CHOICES, SCHEDULES, ArmChoice, RobotName, Schedule
from ..config import SimConfig
from ..core.structures import StructureSpec
from ..errors import ConfigError
from ..jobs.backends import check_backend
from ..params import PARAMS, REPEATS, SWEEP_WORKERS, check_range, param, parse_number, parse_whole
from ..robots import DEFAULT_ROBOT

MAX_POINTS_PER_AXIS = 50
MAX_RUNS = 10_000


def value_text(value: float) -> str:
    """The one spelling of a value: in the CSV, in run keys and on plot ticks."""
    return repr(round(float(value), 9))


@dataclass(frozen=True)
class Axis:
    name: str
    values: tuple[float, ...]

    @property
    def label(self) -> str:
        return param(self.name).label


def parse_axis(name: str, text: str) -> Axis:
    """`start:stop:count` (evenly spaced, both ends included) or `a,b,c`; every value is checked
    by the configuration class that owns it. ConfigError names the parameter and the range."""
    label = param(name).label
    form = f"accepted start:stop:count (count 1 to {MAX_POINTS_PER_AXIS}) or a comma list"
    text = text.strip()
    try:
        if ":" in text:
            parts = text.split(":")
            if len(parts) != 3:
                raise ValueError
            start, stop, count_text = parse_number(parts[0]), parse_number(parts[1]), parts[2]
            count = parse_whole(count_text)
            if not 1 <= count <= MAX_POINTS_PER_AXIS:
                raise ConfigError(f"{label}: {count} points in {text!r}; {form}")
            if count == 1 and start != stop:
                raise ConfigError(f"{label}: one point cannot span {text!r}; {form}")
            step = (stop - start) / (count - 1) if count > 1 else 0.0
            values = tuple(start + i * step for i in range(count))
        else:
            values = tuple(parse_number(v.strip()) for v in text.split(","))
    except ValueError as err:
        if isinstance(err, ConfigError):
            raise
        raise ConfigError(f"{label}: cannot read {text!r}; {form}") from None
    if not values or len(values) > MAX_POINTS_PER_AXIS:
        raise ConfigError(f"{label}: {len(values)} values in {text!r}; {form}")
    values = tuple(round(v, 9) for v in values)
    if len(set(values)) != len(values):
        raise ConfigError(f"{label}: repeated values in {text!r}; {form}")
    for v in values:
        if not math.isfinite(v):
            raise ConfigError(f"{label}: {v} is not a finite number; {form}")
        param(name).check(v)
    return Axis(name, values)


@dataclass(frozen=True)
class SweepRun:
    """One build of the sweep: a grid point and a seed."""

    structure: StructureSpec
    arms: ArmChoice
    params: tuple[tuple[str, float], ...]  # in PARAMS order
    seed: int
    spawn_jitter_mm: float
    robot: RobotName = DEFAULT_ROBOT
    schedule: Schedule = SCHEDULES[0]

    def config(self, base: SimConfig | None = None) -> SimConfig:
        start = base or SimConfig.for_robot(self.robot)  # the robot's scale
        config = replace(start, robot=self.robot, schedule=self.schedule)
        for name, value in self.params:
            config = param(name).apply(config, value)
        layout = replace(config.layout, spawn_jitter_mm=self.spawn_jitter_mm)
        return replace(config, layout=layout, seed=self.seed)

    def key(self) -> tuple[str, ...]:
        """The run's identity as the CSV spells it (see sweep_store.KEY_COLUMNS)."""
        return (
            self.robot,
            self.schedule,
            self.structure.name,
            self.structure.size_text(),
            self.arms,
            *(value_text(v) for _, v in self.params),
            value_text(self.spawn_jitter_mm),
            str(self.seed),
        )


@dataclass(frozen=True)
class SweepConfig:
    """A whole sweep: the grid, the build, the repeats and how the runs are executed."""

    axes: tuple[Axis, ...] = field(default_factory=tuple)  # only the axes the user gave
    structure: StructureSpec = field(default_factory=StructureSpec)
    arms: ArmChoice = "both"
    repeats: int = 1
    spawn_jitter_mm: float = 2.0
    workers: int = 2
    timeout: float = 900.0
    backend: str = "process"
    ray_address: str | None = None
    robot: RobotName = DEFAULT_ROBOT
    schedule: Schedule = SCHEDULES[0]
    retry_failed: bool = False  # run again the points sweep.csv has as crashed or timed out

    def __post_init__(self) -> None:
        SimConfig(robot=self.robot, schedule=self.schedule)  # unknown: one line naming those known
        if self.arms not in ARM_CHOICES:
            raise ConfigError(f"arms: unknown {self.arms!r}; accepted {', '.join(ARM_CHOICES)}")
        REPEATS.check_whole(self.repeats)
        SWEEP_WORKERS.check_whole(self.workers)
        check_range("timeout (s)", self.timeout, 0.0, 86400.0, low_open=True)
        replace(SimConfig().layout, spawn_jitter_mm=self.spawn_jitter_mm)  # range check
        check_backend(self.backend, self.ray_address)
        names = [a.name for a in self.axes]
        if len(set(names)) != len(names):
            raise ConfigError(f"axes: a parameter is given twice ({', '.join(names)})")
        runs = len(self.runs())
        if runs > MAX_RUNS:
            raise ConfigError(f"grid: {runs} runs; accepted at most {MAX_RUNS}")

    def full_axes(self) -> tuple[Axis, ...]:
        """All sweepable parameters in their fixed order, the ones not given at their default."""
        given = {a.name: a for a in self.axes}
        return tuple(given.get(p.name, Axis(p.name, (p.default,))) for p in PARAMS)

    def plot_axes(self) -> tuple[Axis, Axis | None]:
        """The two main axes of the map: the first two (in PARAMS order) with more than one
        value; other varying axes are folded into each cell."""
        full = self.full_axes()
        varying = [a for a in full if len(a.values) > 1]
        x = varying[0] if varying else full[0]
        return x, (varying[1] if len(varying) > 1 else None)

    def runs(self) -> list[SweepRun]:
        """Every run: the grid's points in order, each `repeats` times with seeds 0, 1, ..."""
        points: list[tuple[tuple[str, float], ...]] = [()]
        for axis in self.full_axes():
            points = [p + ((axis.name, v),) for p in points for v in axis.values]
        return [
            SweepRun(
                self.structure, self.arms, p, seed, self.spawn_jitter_mm, self.robot, self.schedule
            )
            for p in points
            for seed in range(self.repeats)
        ]
