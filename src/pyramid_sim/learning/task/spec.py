"""What makes an episode, declared once (`TaskSpec`), as lerobot keeps an environment's options
in one `EnvConfig` and Gymnasium one `EnvSpec`: the structure and its size, the robot and its
settings, how episodes vary, the step rate and action mode, what a policy observes, and the
film. It checks itself once, where it is made, and is carried whole: the environment, a
recording, the API and lerobot's plugin take it, and the command line's flags are its fields.
MuJoCo-free: a spec is checked before any physics is imported.

A new option is one field here, with its doc (`metadata["doc"]`) and its check."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import Any

import numpy as np

from ...choices import (
    ACTION_MODES,
    ARM_CHOICES,
    DEFAULT_VARIATION,
    FPS_CHOICES,
    VARIATIONS,
    ArmChoice,
    in_words,
)
from ...config import MotionConfig, SimConfig
from ...core.structures import StructureSpec
from ...errors import ConfigError
from ...options import RUN_SETTINGS, plain_numbers, resolve
from ...params import BY_NAME, IMAGE_SIZE_TEXT, LINGER
from .observation_names import Observed
from .randomize import ACCEPTED as ACCEPTED_PARTS
from .randomize import check_parts
from .ranges import (
    CAMERA_NAMES,
    DEFAULT_FPS,
    check_camera_names,
    check_image_size,
    control_steps,
)
from .variation import check_level, randomized

SIZES = ("layers", "bricks", "towers", "goals")  # the structure's size (width: the film's)
SETTINGS = (*BY_NAME, *(s for s in RUN_SETTINGS if s != "robot"))  # held in `settings`


def _doc(default: Any, doc: str, flag: str = "", accepted: str = "") -> Any:
    """A field with its default and its declaration: the sentence its flag's help and the
    docs give, the command line's flag (a bool's turns it off), and what it accepts."""
    meta = {"doc": doc, "flag": flag, "accepted": accepted}
    if isinstance(default, (dict, list)):
        return field(default_factory=lambda: type(default)(default), metadata=meta)
    return field(default=default, metadata=meta)


@dataclass(frozen=True)
class TaskSpec:
    """One episode's options, checked on construction: each error a ConfigError naming the
    field and what it accepts. `settings` holds the build's settings by name (friction,
    brick_mass, grip_force, pad_friction, spawn_jitter_mm, seed, schedule); `config` a whole
    SimConfig they apply to."""

    structure: str = _doc("pyramid-even", "the structure built (as `build` takes it)")
    layers: int | None = _doc(None, "the structure's layers (default: its own)")
    bricks: int | None = _doc(None, "the structure's bricks (default: its own)")
    towers: int | None = _doc(None, "the structure's towers (default: its own)")
    goals: str | Path | None = _doc(None, "a goals file, for the `list` structure")
    robot: str | None = _doc(None, "the robot pair (default: the config's, else the first)")
    arms: ArmChoice = _doc("both", "who builds: both arms, or left or right alone")
    variation: str = _doc(
        DEFAULT_VARIATION,
        "how episodes differ: fixed (DE NIRO's layout), layout (the feed spot, the "
        "structure's place and turn drawn per episode) or full (the layout and every "
        "randomization)",
        "--variation",
        ", ".join(VARIATIONS),
    )
    randomize: tuple[str, ...] = _doc(
        (), "parts drawn per episode from its seed, each once", "--randomize", ACCEPTED_PARTS
    )
    fps: int = _doc(
        DEFAULT_FPS,
        "the environment's step rate, a dataset's frames a second (of the 100 Hz control)",
        "--fps",
        in_words(FPS_CHOICES),
    )
    action_mode: str = _doc("joint", "the action", "--action-mode", in_words(ACTION_MODES))
    limit_commands: bool = _doc(True, "commands through the motion generator")
    cameras: tuple[str, ...] = _doc(
        (),
        "the cameras observed, each filmed",
        "--cameras",
        f"{', '.join(CAMERA_NAMES)}; none for no video",
    )
    image_size: tuple[int, int] = _doc(
        (224, 224), "each camera's pixels (height, width)", "--image-size", IMAGE_SIZE_TEXT
    )
    brick_poses: bool = _doc(
        True,
        "the bricks' poses (and which goals hold a brick, judged from them) observed; "
        "--no-brick-poses leaves them out: a policy that sees the bricks through its cameras "
        "alone",
        "--no-brick-poses",
    )
    all_goals: bool = _doc(
        True,
        "every goal observed; --next-goals-only leaves all but each arm's next out, so the "
        "observation's width is the same whatever the structure's size",
        "--next-goals-only",
    )
    linger: float = _doc(
        0.0,
        "seconds an episode that built goes on: the last release and the hands leaving, "
        "filmed and taught as the first",
        "--linger",
        LINGER.text,
    )
    footprints: bool = _doc(True, "the targets drawn on the table for the cameras")
    render_mode: str | None = _doc(None, "rgb_array: render() films camera_name")
    width: int = _doc(640, "the film's width in pixels (render())")
    height: int = _doc(480, "the film's height in pixels (render())")
    camera_name: str = _doc("overview", "the camera render() films")
    settings: Mapping[str, Any] = _doc({}, "the build's settings by name")
    config: SimConfig | None = _doc(None, "a whole SimConfig the settings apply to")

    def __post_init__(self) -> None:
        for name, value in plain_numbers({n: getattr(self, n) for n in NUMBERS}).items():
            object.__setattr__(self, name, value)  # numpy's numbers as Python's own
        for name in BOOLS:
            object.__setattr__(self, name, strict_bool(name, getattr(self, name)))
        if self.action_mode not in ACTION_MODES:
            raise ConfigError(
                f"action mode: unknown {self.action_mode!r}; accepted {in_words(ACTION_MODES)}"
            )
        if self.render_mode not in (None, "rgb_array"):
            raise ConfigError(f"render mode: unknown {self.render_mode!r}; accepted rgb_array")
        if self.arms not in ARM_CHOICES:
            raise ConfigError(f"arms: unknown {self.arms!r}; accepted {in_words(ARM_CHOICES)}")
        unknown = [k for k in self.settings if k not in SETTINGS]
        if unknown:
            raise ConfigError(f"settings: unknown {unknown[0]!r}; accepted {', '.join(SETTINGS)}")
        check_level(self.variation)
        object.__setattr__(self, "randomize", _parts(self.randomize))
        control_steps(self.fps, MotionConfig().control_dt)
        object.__setattr__(self, "cameras", check_camera_names(self.cameras))
        object.__setattr__(self, "image_size", check_image_size(self.image_size))
        check_image_size((self.height, self.width))
        check_camera_names((self.camera_name,))
        object.__setattr__(self, "linger", LINGER.checked(self.linger))
        # the settings and the structure's size, each checked, resolved once
        object.__setattr__(self, "_resolved", self._resolve())

    @classmethod
    def of(cls, structure: str | TaskSpec = "pyramid-even", **keywords: Any) -> TaskSpec:
        """A spec from keywords as `gym.make` and `pyramid_sim.record` take them: the fields,
        the settings by name, or a spec whole (no keyword beside it). ConfigError for a
        keyword that is none of these, naming every one accepted."""
        if isinstance(structure, TaskSpec):
            if keywords:
                raise ConfigError(
                    f"keywords: {', '.join(keywords)} beside a whole TaskSpec; accepted the "
                    "spec alone (dataclasses.replace(spec, ...) changes it)"
                )
            return structure
        check_keywords(keywords)
        own = {k: v for k, v in keywords.items() if k not in SETTINGS}
        settings = {k: v for k, v in keywords.items() if k in SETTINGS}
        return cls(structure, **own, settings=settings)

    def resolved(self) -> tuple[SimConfig, StructureSpec]:
        """The build's settings and the structure at its size, as `build` resolves them."""
        resolved: tuple[SimConfig, StructureSpec] = self.__dict__["_resolved"]
        return resolved

    def _resolve(self) -> tuple[SimConfig, StructureSpec]:
        options = dict(self.settings)
        if self.robot is not None:
            options["robot"] = self.robot
        options.update({k: getattr(self, k) for k in SIZES if getattr(self, k) is not None})
        return resolve(self.structure, self.config, options, own=())

    @property
    def observed(self) -> Observed:
        """What the observation holds beyond the arms' own (`Observed`)."""
        return Observed(self.brick_poses, self.all_goals)

    @property
    def sizes(self) -> dict[str, Any]:
        """The size options given (the structure's defaults stand for the rest)."""
        return {k: getattr(self, k) for k in SIZES if getattr(self, k) is not None}

    @property
    def randomized(self) -> tuple[str, ...]:
        """The randomization parts each episode draws (every one at `full`)."""
        return randomized(self.variation, check_parts(self.randomize))


BOOLS = ("limit_commands", "brick_poses", "all_goals", "footprints")
NUMBERS = ("layers", "bricks", "towers", "fps", "linger", "width", "height")
FIELDS = tuple(f.name for f in fields(TaskSpec))
# the keywords a spec is made from: its fields and the settings by name
ACCEPTED = (*(f for f in FIELDS if f != "settings"), *SETTINGS)


def check_keywords(keywords: Mapping[str, Any], also: tuple[str, ...] = ()) -> None:
    """ConfigError for the first keyword that is neither a spec's (ACCEPTED) nor one of
    `also` (a caller's own), naming every one accepted."""
    accepted = tuple(dict.fromkeys((*ACCEPTED, *also)))
    for name in keywords:
        if name not in accepted:
            raise ConfigError(f"keyword: unknown {name!r}; accepted {', '.join(accepted)}")


def _parts(value: Any) -> tuple[str, ...]:
    """The randomization parts as given, a tuple ("none" is none); ConfigError for one name
    alone (a str reads as its letters) or a part that is not one."""
    if not isinstance(value, str):
        try:
            value = tuple(value)
        except TypeError:
            raise ConfigError(
                f"randomize: {value!r} is not a sequence; accepted {ACCEPTED_PARTS}"
            ) from None
    return () if check_parts(value) == () else value


def strict_bool(name: str, value: Any) -> bool:
    """`value` if it is a bool (numpy's too); ConfigError naming `name` otherwise (a word such
    as "no" is not taken as true)."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise ConfigError(f"{name.replace('_', ' ')}: {value!r} is not a bool; accepted True or False")
