"""User options resolved into settings and a structure: below `api` and the learning room,
so both read keywords the same way without importing each other."""

from __future__ import annotations

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
    if goals is not None:
        from .core.goals import load_goals

        config = config or SimConfig()
        table_z = config.layout.table_top_z + config.brick.height / 2
        targets = load_goals(Path(goals), config.brick, table_z)
    return StructureSpec(
        name,
        layers=layers,
        bricks=bricks,
        width=width,
        towers=towers,
        goals=targets,
        goals_source=Path(goals).name if goals is not None else "",
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
