"""A policy trained with `lerobot-train` on a recorded dataset, driven in the environment as
`lerobot-eval` drives it: the checkpoint's own pre- and post-processors (normalization) around
`select_action`, on the CPU. Needs lerobot (and torch), which pyramid_sim does not depend on:
it is imported here only, when a checkpoint folder is asked for."""

from __future__ import annotations

import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np

from ...errors import ConfigError, MachineError
from ..recording.episode import task_text
from .lerobot_env import lerobot_keys


def one_thread() -> None:
    """torch on one thread unless OMP_NUM_THREADS says otherwise: these policies are small,
    and a pool of threads beside MuJoCo's on a busy machine waits on itself (a Diffusion
    Policy episode ran at 1.1 s a step in torch's own pool on a loaded 2-core machine, ten
    times slower than on one thread)."""
    import os

    import torch

    if "OMP_NUM_THREADS" not in os.environ:
        torch.set_num_threads(1)


@contextmanager
def own_temporary_files() -> Iterator[None]:
    """Python's temporary files in a folder of ours, removed after: lerobot's
    `PreTrainedConfig.from_pretrained` writes the config it parses to a temporary file it
    never removes (`NamedTemporaryFile(delete=False)`, lerobot 0.6), so every policy loaded
    left a tmp*.json in /tmp (two a row, from baseline.py's films)."""
    before = tempfile.tempdir
    with tempfile.TemporaryDirectory(prefix="pyramid-sim-lerobot-") as folder:
        tempfile.tempdir = folder
        try:
            yield
        finally:
            tempfile.tempdir = before


class LerobotPolicy:
    """The policy saved in `folder` (a checkpoint's pretrained_model: config.json and
    model.safetensors), for the BuildEnv `env`."""

    def __init__(self, folder: Path, env: Any) -> None:
        if not (folder / "config.json").is_file():
            raise ConfigError(
                f"policy: {str(folder)!r} holds no config.json; accepted a lerobot checkpoint's "
                "pretrained_model folder"
            )
        try:
            from lerobot.configs.policies import PreTrainedConfig
            from lerobot.envs.utils import preprocess_observation
            from lerobot.policies import make_pre_post_processors
            from lerobot.policies.factory import get_policy_class
        except ImportError:
            raise lerobot_missing() from None
        check_checkpoint_files(folder)
        one_thread()
        with own_temporary_files():
            config = PreTrainedConfig.from_pretrained(str(folder))
            config.device = "cpu"
            self.policy = get_policy_class(config.type).from_pretrained(str(folder), config=config)
        self.policy.eval()
        self.pre, self.post = make_pre_post_processors(
            policy_cfg=self.policy.config,
            pretrained_path=str(folder),
            preprocessor_overrides={"device_processor": {"device": "cpu"}},
        )
        self._to_tensors = preprocess_observation
        self.task = task_text(env.unwrapped)
        self.units = env.unwrapped.lerobot_units
        self.action_units = env.unwrapped.action_units

    def reset(self) -> None:
        self.policy.reset()  # an action chunk is not carried into the next episode

    def act(self, observation: Any) -> np.ndarray:
        import torch

        batch = {
            k: (np.expand_dims(v, 0) if k != "pixels" else {c: i[None] for c, i in v.items()})
            for k, v in lerobot_keys(observation, self.units).items()
        }
        tensors = self._to_tensors(batch)
        tensors["task"] = [self.task]
        with torch.inference_mode():
            action = self.post(self.policy.select_action(self.pre(tensors)))
        theirs = action.to("cpu").numpy()[0]  # in lerobot's units for the robot, as recorded
        return np.asarray(self.action_units.from_lerobot(theirs), dtype=np.float32)


CHECKPOINT_FILES = ("model.safetensors", "policy_preprocessor.json", "policy_postprocessor.json")


def check_checkpoint_files(folder: Path) -> None:
    """ConfigError naming the first file of a checkpoint that is missing, or a weights file
    cut short (its safetensors header names more bytes than it holds): lerobot would fail on
    either with a traceback of its own."""
    for name in CHECKPOINT_FILES:
        if not (folder / name).is_file():
            raise ConfigError(
                f"policy: {str(folder)!r} holds no {name}; accepted a lerobot checkpoint's "
                f"pretrained_model folder (config.json, {', '.join(CHECKPOINT_FILES)})"
            )
    problem = safetensors_problem(folder / CHECKPOINT_FILES[0])
    if problem:
        raise ConfigError(
            f"policy: {str(folder / CHECKPOINT_FILES[0])!r} {problem}; accepted a whole "
            "checkpoint (copy it again, or train it again)"
        )


def safetensors_problem(path: Path) -> str:
    """What is wrong with `path` as a safetensors file, read from its header alone (8 bytes
    of header length, the JSON header, then the tensors' bytes), or ""."""
    import json

    size = path.stat().st_size
    with open(path, "rb") as f:
        head = f.read(8)
        length = int.from_bytes(head, "little") if len(head) == 8 else -1
        if length < 0 or 8 + length > size:
            return f"is cut short ({size} bytes, not even its header)"
        try:
            header = json.loads(f.read(length))
            ends = [int(t["data_offsets"][1]) for k, t in header.items() if k != "__metadata__"]
        except (ValueError, TypeError, KeyError, IndexError, AttributeError) as err:
            return f"is not a safetensors file ({type(err).__name__} in its header)"
    needed = 8 + length + max(ends, default=0)
    if size < needed:
        return f"is cut short ({size} bytes of the {needed} its header names)"
    return ""


def lerobot_missing() -> MachineError:
    """The error for a checkpoint where lerobot cannot be imported."""
    return MachineError(
        "policy: a lerobot checkpoint needs lerobot, which is not installed here (it brings "
        "torch: install it in a venv of its own with pyramid_sim, see docs/evaluation.md)"
    )
