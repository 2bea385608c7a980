"""The one table of physics parameters a user turns.

Each row generates a `build` flag and a `sweep` axis (same flag, taking a grid), their help text
with the default and the accepted range, the validation in the settings dataclass that owns
the value, and a `sweep.csv` column. Adding a knob is one row here plus the model code that
uses it; `tests/test_params.py` checks that every row reaches the compiled model.
Pure: no MuJoCo, and no import of the settings dataclasses (they import this table).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

from .errors import ConfigError


@dataclass(frozen=True)
class Param:
    """One physics parameter: where it lives in the settings, its unit, default and range."""

    name: str  # the keyword in Python, the sweep.csv column, the flag with dashes
    label: str  # as a person reads it, in messages and on plots
    unit: str
    section: str  # the SimConfig field holding it: "brick" or "gripper"
    field: str  # the field of that section
    default: float
    low: float
    high: float
    low_open: bool  # low itself is refused
    sets: str  # what it sets in the model

    @property
    def flag(self) -> str:
        return "--" + self.name.replace("_", "-")

    @property
    def range_text(self) -> str:
        return span_text(self.low, self.high, self.low_open)

    @property
    def help(self) -> str:
        unit = f" {self.unit}" if self.unit else ""
        return (
            f"{self.sets}; accepted {self.range_text}{unit} (default {self.default:g}, or the "
            "robot's own at its scale)"
        )

    def check(self, value: Any) -> None:
        """ConfigError naming the parameter and its range unless `value` is accepted."""
        check_range(self.label, value, self.low, self.high, low_open=self.low_open)

    def read(self, config: Any) -> float:
        return float(getattr(getattr(config, self.section), self.field))

    def apply(self, config: Any, value: float) -> Any:
        """`config` (a SimConfig) with this parameter set to `value` (validated by its owner)."""
        section = replace(getattr(config, self.section), **{self.field: value})
        return replace(config, **{self.section: section})


PARAMS: tuple[Param, ...] = (
    Param(
        "friction",
        "brick friction",
        "",
        "brick",
        "friction",
        1.0,
        0.0,
        5.0,
        True,
        "sliding friction of the brick geoms",
    ),
    Param(
        "brick_mass",
        "brick mass (kg)",
        "kg",
        "brick",
        "mass",
        0.5,
        0.0,
        5.0,
        True,
        "mass of each brick",
    ),
    Param(
        "grip_force",
        "grip force (N)",
        "N",
        "gripper",
        "force",
        20.0,
        0.0,
        140.0,
        True,
        "squeeze of each finger pad (the gripper actuator's force limit)",
    ),
    Param(
        "pad_friction",
        "pad friction",
        "",
        "gripper",
        "pad_friction",
        1.0,
        0.0,
        5.0,
        True,
        "sliding friction of the finger pads",
    ),
)
BY_NAME = {p.name: p for p in PARAMS}


def param(name: str) -> Param:
    """The row called `name`; ConfigError listing the rows otherwise."""
    if name not in BY_NAME:
        raise ConfigError(f"parameter: unknown {name!r}; accepted {', '.join(BY_NAME)}")
    return BY_NAME[name]


def default(section: str, field: str) -> float:
    """The table's default for a settings field (the dataclasses take their defaults here)."""
    return next(p.default for p in PARAMS if (p.section, p.field) == (section, field))


def check_section(section: str, settings: Any) -> None:
    """Validate every table parameter held by `settings`, the `section` part of a SimConfig."""
    for p in PARAMS:
        if p.section == section:
            p.check(getattr(settings, p.field))


@dataclass(frozen=True)
class Bound:
    """An accepted range held in one place: the check that refuses a value and the help text
    that states the range both read it, so the two cannot drift apart."""

    name: str  # as a person reads it, in messages
    low: float
    high: float
    low_open: bool = False  # low itself is refused

    @property
    def text(self) -> str:
        return span_text(self.low, self.high, self.low_open)

    def check(self, value: Any) -> None:
        """ConfigError naming the value and this range unless `value` is within it."""
        check_range(self.name, value, self.low, self.high, low_open=self.low_open)

    def checked(self, value: Any) -> float:
        """`value` as a float, once `check` has let it through."""
        self.check(value)
        return float(value)

    @property
    def whole_text(self) -> str:
        """`low to high`: the range of a count, its ends written whole (1 to 10000000)."""
        return f"{int(self.low)} to {int(self.high)}"

    def check_whole(self, value: Any) -> None:
        """ConfigError unless `value` is a whole number within the range."""
        if isinstance(value, bool) or not isinstance(value, int):
            raise ConfigError(
                f"{self.name}: {value!r} is not a whole number; accepted {self.whole_text}"
            )
        if not self.low <= value <= self.high:
            raise ConfigError(f"{self.name}: {value!r} is out of range; accepted {self.whole_text}")


# The ranges of a recording's and an evaluation's counts, read by their checks and their help.
EPISODES = Bound("episodes", 1, 100_000)
WORKERS = Bound("workers", 1, 64)
SWEEP_WORKERS = Bound("workers", 1, 256)  # a sweep's runs at once: a Ray cluster has many
REPEATS = Bound("repeats", 1, 100)  # a sweep's runs a grid point
MAX_STEPS = Bound("max steps", 1, 10_000_000)
NOISE = Bound("noise", 0.0, 0.05)  # rad: DART's offset on the executed joint targets
LINGER = Bound("linger", 0.0, 10.0)  # s an episode goes on after its build succeeded
BETA = Bound("beta", 0.0, 1.0)  # DAgger's: the share of an episode's spans the expert drives
# m a learner's hand may drift from the expert's way before the expert takes over (HG-DAgger)
TAKEOVER = Bound("takeover", 0.0, 0.2, low_open=True)
IMAGE_HEIGHT = Bound("image height", 16, 1080)  # pixels, even
IMAGE_WIDTH = Bound("image width", 16, 1920)
IMAGE_SIZE_TEXT = f"even, {IMAGE_HEIGHT.whole_text} high and {IMAGE_WIDTH.whole_text} wide"


def image_size_fits(height: int, width: int) -> bool:
    """Whether images of `height` x `width` pixels can be rendered: even, within the bounds."""
    return (
        IMAGE_HEIGHT.low <= height <= IMAGE_HEIGHT.high
        and IMAGE_WIDTH.low <= width <= IMAGE_WIDTH.high
        and height % 2 == width % 2 == 0
    )


def span_text(low: float, high: float, low_open: bool = False) -> str:
    """`[low, high]`, or `(low, high]` when low is refused, numbers written compactly."""
    return f"{'(' if low_open else '['}{low:g}, {high:g}]"


def parse_number(text: str) -> float:
    """`text` as a float, written as a person writes numbers: ValueError for what Python's
    float() reads but nobody means, digit separators (`0_5` is 5 to float) and non-ASCII
    digits. Range, NaN and inf are the settings' checks."""
    return float(_plain(text))


def parse_whole(text: str) -> int:
    """`text` as an int, refusing what `parse_number` refuses."""
    return int(_plain(text))


def _plain(text: str) -> str:
    if "_" in text or not text.isascii():
        raise ValueError(f"{text!r} is not a plain number")
    return text


def check_range(name: str, value: Any, low: float, high: float, *, low_open: bool = False) -> None:
    """Raise ConfigError unless low <= value <= high (low < value when low_open)."""
    span = span_text(low, high, low_open)
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ConfigError(f"{name}: {value!r} is not a number; accepted {span}")
    ok = math.isfinite(value) and (value > low if low_open else value >= low) and value <= high
    if not ok:
        raise ConfigError(f"{name}: {value:g} is out of range; accepted {span}")
