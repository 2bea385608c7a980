"""Whether a run may add its episodes to a dataset: a dataset is one recording, so a run whose
settings would shape its files otherwise is refused, naming the first setting that differs
and both values; what only drove an episode (DART's noise, a DAgger round's policy and share)
may differ, each episode's record saying it."""

from __future__ import annotations

import json
from dataclasses import asdict
from pathlib import Path
from typing import Any

from ...errors import ConfigError
from ..task.observation_names import OBSERVED, Observed
from .record_config import RecordConfig

# What may differ between the runs that fill one dataset: none of it shapes an episode's files.
# What drove an episode (DART's noise, a DAgger round's policy and its share) is among it: a
# dataset grows by DAgger's rounds, and each episode's record says what drove it.
RUN_ONLY = ("episodes", "workers", "backend", "ray_address", "noise", "policy", "beta", "takeover")
DRIVER = ("policy", "beta", "takeover")  # kept in an episode's record only where a policy drove it
# Settings added since the first recordings, as an episode recorded before them had them (and
# as a record leaves out the one whose default it keeps: the bricks' poses observed).
# What is observed (`Observed`) is among them, each at its default.
LATER_SETTINGS = {"action_mode": "joint", "linger": 0.0, **Observed()._asdict()}


def settings_of(config: RecordConfig) -> dict[str, Any]:
    """The recording's settings as its episode records keep them (JSON's types); a DAgger
    round's driver is kept apart (`driver`), so an expert's recording reads as ever."""
    doc: dict[str, Any] = json.loads(json.dumps(asdict(config), default=str))
    for name in DRIVER:
        del doc[name]
    for observed in OBSERVED:  # a default, which records made before held
        if doc[observed]:
            del doc[observed]
    return doc


def check_same_recording(
    out: Path, records: dict[int, dict[str, Any]], config: RecordConfig
) -> None:
    """ConfigError if `out` holds episodes recorded with other settings (the structure, its
    size and build settings, the frame rate, cameras, image size, variation, randomized
    parts, first seed, command limits, linger, whether the bricks' poses are observed): each
    shapes the files, and a dataset is one recording."""
    wanted = {**LATER_SETTINGS, **settings_of(config)}
    for index, rec in sorted(records.items()):
        kept = {**LATER_SETTINGS, **rec.get("config", {})}
        filmed = bool(kept.get("cameras")) or bool(config.cameras)  # or no image has a size
        for name in wanted:
            if name in RUN_ONLY or kept.get(name) == wanted[name]:
                continue
            if name == "image_size" and not filmed:
                continue
            setting, was, now = _difference(name, kept.get(name), wanted[name])
            raise ConfigError(
                f"out: {str(out)!r} holds episodes of another recording (episode {index} has "
                f"{setting} {_short(was)}, this run {_short(now)}); accepted a new folder, or "
                "the same recording's settings"
            )


def _difference(name: str, was: Any, now: Any) -> tuple[str, Any, Any]:
    """The first setting under `name` where `was` and `now` differ (`options.config.seed`),
    and its two values: a long setting cut short would show both the same."""
    if isinstance(was, dict) and isinstance(now, dict):
        for key in sorted(set(was) | set(now)):
            if was.get(key) != now.get(key):
                return _difference(f"{name}.{key}", was.get(key), now.get(key))
    return name, was, now


def _short(value: Any) -> str:
    text = json.dumps(value)
    return text if len(text) <= 60 else text[:57] + "..."
