"""User options resolved into settings and a structure: below `api` and the learning room,
so both read keywords the same way without importing each other."""

from __future__ import annotations

import numbers
import os
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from typing import Any

from .config import SimConfig
from .core.structures import StructureSpec
from .errors import ConfigError
from .params import BY_NAME

RUN_SETTINGS = ("spawn_jitter_mm", "seed", "robot", "schedule")


def settings(config: SimConfig | None = None, **values: Any) -> SimConfig:
    """`config` (default: the robot's settings at its scale, SimConfig.for_robot) with the
    named settings applied; ConfigError for a name that is not a setting, listing those that
    are."""
    _refuse_unknown(values, ())
    values = plain_numbers(values)
    if config is not None and not isinstance(config, SimConfig):
        raise ConfigError(
            f"config: {config!r} is not a SimConfig; accepted pyramid_sim.SimConfig(...) or None"
        )
    if config is None:
        config = SimConfig.for_robot(values.get("robot", SimConfig().robot))
    for name, value in values.items():
        if name in BY_NAME:
            config = BY_NAME[name].apply(config, value)
        elif name == "spawn_jitter_mm":
            config = replace(config, layout=replace(config.layout, spawn_jitter_mm=value))
        else:
            config = replace(config, **{name: value})
    return config


def _refuse_unknown(values: dict[str, Any], also: tuple[str, ...]) -> None:
    """ConfigError naming the first keyword that is neither a setting nor one of `also`, and
    every keyword accepted."""
    accepted = (*BY_NAME, *RUN_SETTINGS, "config", *also)
    for name in values:
        if name not in accepted:
            raise ConfigError(f"setting: unknown {name!r}; accepted {', '.join(accepted)}")


SIZE_KEYWORDS = ("layers", "bricks", "width", "towers", "goals")


def structure(
    name: str = "pyramid-even",
    *,
    layers: int | None = None,
    bricks: int | None = None,
    width: int | None = None,
    towers: int | None = None,
    goals: str | Path | None = None,
    config: SimConfig | None = None,
) -> StructureSpec:
    """A structure at a size (a goals file for `list`); the options left out take the
    structure's defaults."""
    targets = None
    goals_path = path_argument(goals, "goals", "a JSON or CSV file's path")
    if goals_path is not None:
        from .core.goals import load_goals

        config = config or SimConfig()
        table_z = config.layout.table_top_z + config.brick.height / 2
        targets = load_goals(goals_path, config.brick, table_z)
    sizes = plain_numbers({"layers": layers, "bricks": bricks, "width": width, "towers": towers})
    return StructureSpec(
        name,
        **sizes,
        goals=targets,
        goals_source=goals_path.name if goals_path is not None else "",
    )


def resolve(
    name: str, config: SimConfig | None, options: dict[str, Any], own: tuple[str, ...]
) -> tuple[SimConfig, StructureSpec]:
    """Settings and structure from one set of keywords: the size options (SIZE_KEYWORDS) go
    to the structure, the rest are settings. An unknown keyword's error names every keyword the
    caller takes (settings, size options and its `own`); a bad value's error is the one line
    the command line gives."""
    _refuse_unknown(options, SIZE_KEYWORDS + own)
    sizes = {k: options.pop(k) for k in SIZE_KEYWORDS if k in options}
    config = settings(config, **options)
    return config, structure(name, config=config, **sizes)


def plain_numbers(values: dict[str, Any]) -> dict[str, Any]:
    """`values` with numpy's numbers (np.int64(2), np.float32(0.5)) as Python's own, which the
    settings check and JSON writes: numpy numbers are numbers (a numpy bool stays refused)."""
    return {k: _plain(v) for k, v in values.items()}


def _plain(value: Any) -> Any:
    if isinstance(value, numbers.Number) and type(value).__module__ == "numpy":
        return value.item()  # type: ignore[attr-defined]
    return value


def path_argument(value: Any, what: str, accepted: str) -> Path | None:
    """`value` as a Path (None stays None); ConfigError for what is not a path's text or a
    path object (bytes, a number), naming `what` and `accepted`."""
    if value is None:
        return None
    if isinstance(value, (str, os.PathLike)) and not isinstance(os.fspath(value), bytes):
        return Path(value)
    raise ConfigError(f"{what}: {value!r} is not a path; accepted {accepted}, as a str or Path")


def callback_argument(value: Any, what: str) -> Callable[..., Any] | None:
    """`value` if it can be called (or None); ConfigError naming `what` otherwise, before a
    run that would call it halfway."""
    if value is None or callable(value):
        return value
    raise ConfigError(f"{what}: {value!r} cannot be called; accepted a function, or None")


def names_argument(value: Any, what: str, accepted: str) -> tuple[str, ...]:
    """`value` as a tuple of names; ConfigError for one name alone (a str reads as its
    letters) and for what is not a sequence of str."""
    if isinstance(value, str):
        raise ConfigError(
            f"{what}: {value!r} is one name, not a sequence of them; accepted a tuple of {accepted}"
        )
    try:
        names = tuple(value)
    except TypeError:
        raise ConfigError(
            f"{what}: {value!r} is not a sequence; accepted a tuple of {accepted}"
        ) from None
    if not all(isinstance(n, str) for n in names):
        raise ConfigError(
            f"{what}: {value!r} holds other than names; accepted a tuple of {accepted}"
        )
    return names
