"""What a lerobot checkpoint's training saw, read from the train_config.json lerobot saves
beside it (no lerobot import): the recording it learned from (pyramid_sim's metadata and
lerobot's info.json), or else the pyramid_sim env it was scored in during training. Its
actions mean what they meant there: another mode or rate reads them as something else."""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ...errors import ConfigError
from ...robots import PRESETS
from ..task.lerobot_units import robot_type
from ..task.observation_names import Observed

# pyramid_sim's own metadata in a recording (recording/record.py's DATASET_DOC), and lerobot's
DATASET_DOC = "meta/pyramid_sim/dataset.json"
INFO = "meta/info.json"
ENV_TYPE = "pyramid_sim"  # the plugin's `--env.type`
OLD_ACTION_MODE = "joint"  # a recording made before the modes says none: it is joint targets


@dataclass(frozen=True)
class Trained:
    """The task a checkpoint was trained on, and where that was read (for messages). `robot`
    is None where the recording's robot_type is none of the presets'."""

    source: str
    robot: str | None
    structure: str
    size: dict[str, int]
    variation: str
    fps: int
    action_mode: str
    observed: Observed = Observed()  # what its policy's observation held beyond the arms' own


def read_training(folder: Path) -> Trained | None:
    """What the checkpoint in `folder` was trained on, or None where its train_config.json is
    missing, or names no pyramid_sim recording that is there and no pyramid_sim env.
    ConfigError for a file that cannot be read."""
    path = folder / "train_config.json"
    if not path.is_file():
        return None
    train = _json(path)
    root = dataset_root(folder, train)
    if root is not None:
        return _from_dataset(root)
    env = train.get("env") or {}
    if env.get("type") == ENV_TYPE:
        return _from_env(env, path)
    return None


def dataset_root(folder: Path, train: dict[str, Any]) -> Path | None:
    """The recording `train` names, where it holds pyramid_sim's metadata: its root as given
    (relative to here, or to where training ran, read off `output_dir`), or lerobot's local
    copy of its repo_id ($HF_LEROBOT_HOME/repo_id) where it gave no root."""
    dataset = train.get("dataset") or {}
    root, repo = dataset.get("root"), dataset.get("repo_id")
    candidates = []
    if root is not None:
        candidates.append(Path(root))
        ran_in = _training_folder(folder, train.get("output_dir"))
        if not Path(root).is_absolute() and ran_in is not None:
            candidates.append(ran_in / root)
    elif repo:
        candidates.append(_lerobot_home() / repo)
    for candidate in candidates:
        if (candidate / DATASET_DOC).is_file() and (candidate / INFO).is_file():
            return candidate
    return None


def _training_folder(folder: Path, output_dir: str | None) -> Path | None:
    """Where a training whose relative `output_dir` saved `folder`
    (<output_dir>/checkpoints/<step>/pretrained_model) ran, or None if it cannot be told."""
    if not output_dir or Path(output_dir).is_absolute():
        return None
    base = folder.resolve().parent.parent.parent
    for part in reversed(Path(output_dir).parts):
        if base.name != part:
            return None
        base = base.parent
    return base


def _lerobot_home() -> Path:
    """lerobot's local datasets (lerobot.utils.constants.HF_LEROBOT_HOME)."""
    cache = os.environ.get("XDG_CACHE_HOME", "~/.cache")
    hub = os.environ.get("HF_HOME") or os.path.join(cache, "huggingface")
    return Path(os.environ.get("HF_LEROBOT_HOME") or Path(hub) / "lerobot").expanduser()


def _from_dataset(root: Path) -> Trained:
    doc, info = _json(root / DATASET_DOC), _json(root / INFO)
    robots = {robot_type(r): name for name, r in PRESETS.items()}
    try:
        return Trained(
            f"its dataset {str(root)!r}",
            robots.get(info.get("robot_type", "")),
            doc["structure"],
            {k: int(v) for k, v in doc["size"].items()},
            doc["variation"],
            int(info["fps"]),
            doc.get("action_mode", OLD_ACTION_MODE),
            Observed.read(doc),
        )
    except (KeyError, TypeError, ValueError, AttributeError) as err:
        raise ConfigError(
            f"policy: its dataset {str(root)!r} cannot be read ({type(err).__name__}: {err}); "
            "accepted a recording `pyramid-sim record` wrote"
        ) from None


def _from_env(env: dict[str, Any], path: Path) -> Trained:
    try:
        return Trained(
            f"the env in {str(path)!r}",
            env["robot"],
            env["task"],
            {"layers": int(env["layers"])},
            env["variation"],
            int(env["fps"]),
            env["action_mode"],
            Observed.read(env),
        )
    except (KeyError, TypeError, ValueError) as err:
        raise ConfigError(
            f"policy: the env in {str(path)!r} cannot be read ({type(err).__name__}: {err}); "
            "accepted the one lerobot-train --env.type=pyramid_sim saves"
        ) from None


def _json(path: Path) -> dict[str, Any]:
    try:
        doc = json.loads(path.read_text())
    except (OSError, ValueError) as err:
        raise ConfigError(f"policy: {str(path)!r} cannot be read ({err})") from None
    if not isinstance(doc, dict):
        raise ConfigError(f"policy: {str(path)!r} cannot be read (not a JSON object)")
    return doc
