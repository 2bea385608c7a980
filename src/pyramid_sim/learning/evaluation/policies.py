"""The policies an evaluation drives: the scripted expert, two bounds (`zero` holds still,
`random` samples the action space), a `module:factory` of the user's, and a lerobot checkpoint
folder (where lerobot is installed). Each is an object with `act(observation) -> action`
and `reset()`, made for one environment."""

from __future__ import annotations

import importlib
import os
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from ...errors import ConfigError, Terminated
from ..recording.policy_calls import exits_raised

NAMED = ("expert", "zero", "random")


class Policy(Protocol):
    """What an evaluation drives: reset at each episode's start, then asked once a step."""

    def reset(self) -> None: ...

    def act(self, observation: Any) -> np.ndarray: ...


class HoldStill:
    """The `zero` policy: every joint held where the episode began, the hands as they were."""

    def __init__(self, env: Any) -> None:
        self.env = env.unwrapped
        self._held: np.ndarray | None = None

    def reset(self) -> None:
        self._held = None

    def act(self, observation: Any) -> np.ndarray:
        if self._held is None:
            self._held = self.env.held_command()
        return self._held


class RandomActions:
    """The `random` policy: the action space sampled, seeded by the episode's seed."""

    def __init__(self, env: Any) -> None:
        self.env = env.unwrapped

    def reset(self) -> None:
        self.env.action_space.seed(self.env.seed_of_episode)

    def act(self, observation: Any) -> np.ndarray:
        return np.asarray(self.env.action_space.sample())


class _Function:
    """A plain function of the observation as a policy."""

    def __init__(self, function: Any) -> None:
        self.function = function

    def reset(self) -> None:
        return None

    def act(self, observation: Any) -> np.ndarray:
        return np.asarray(self.function(observation))


ACCEPTED = f"{', '.join(NAMED)}, module:factory, or a lerobot checkpoint folder"


def check_spec(spec: object) -> str:
    """`spec` as the text that names a policy (a folder's path as its text); ConfigError for
    what cannot name one: not text, or empty (which would be the working folder)."""
    if isinstance(spec, os.PathLike):
        spec = os.fspath(spec)
    if not isinstance(spec, str) or not spec.strip():
        raise ConfigError(f"policy: {spec!r} is not one; accepted {ACCEPTED}")
    return spec


def make_policy(spec: str, env: Any) -> Policy:
    """The policy `spec` names for `env`: expert, zero, random, `module:factory` (called with
    the environment, it returns a policy, or a function of the observation), or a lerobot
    checkpoint folder. ConfigError naming what is accepted otherwise, and for a module or
    factory that raises (or exits) instead; MachineError for a checkpoint where lerobot is not
    installed."""
    spec = check_spec(spec)
    if spec == "expert":
        from ..expert.policy import ExpertPolicy  # MuJoCo: once a policy is made

        return ExpertPolicy(env)
    if spec == "zero":
        return HoldStill(env)
    if spec == "random":
        return RandomActions(env)
    if Path(spec).is_dir():
        from ..lerobot_plugin.lerobot_policy import LerobotPolicy

        return LerobotPolicy(Path(spec), env)
    module, _, name = spec.partition(":")
    if not module or not name:
        raise ConfigError(f"policy: {spec!r} is not one; accepted {ACCEPTED}")
    factory = _factory(spec, module, name)
    try:
        with exits_raised():
            made = factory(env)
    except Terminated:
        raise
    except (Exception, SystemExit) as err:  # the user's code: one line naming it
        raise ConfigError(
            f"policy: {spec!r} failed to make its policy ({_raised(err)}); "
            "accepted a factory that returns a policy for the environment"
        ) from err
    if hasattr(made, "act"):
        if not hasattr(made, "reset"):
            made.reset = lambda: None
        return made
    if callable(made):
        return _Function(made)
    raise ConfigError(
        f"policy: {spec!r} returned {type(made).__name__}; accepted an object with act(), or a "
        "function of the observation"
    )


def _factory(spec: str, module: str, name: str) -> Any:
    """`module`'s `name`, imported; ConfigError naming what went wrong where the module is
    missing, fails to import (a syntax error, an exception, an exit at import) or lacks
    `name`: the user's code, told in one line."""
    try:
        imported = importlib.import_module(module)
    except ImportError as err:
        raise ConfigError(
            f"policy: {spec!r} cannot be loaded ({err}); accepted module:factory, the module "
            "on the import path (the current folder is on it)"
        ) from None
    except (Exception, SystemExit) as err:  # its code ran and failed (SyntaxError among them)
        raise ConfigError(
            f"policy: {spec!r} cannot be loaded: importing {module!r} raised {_raised(err)}; "
            "accepted module:factory, a module that imports"
        ) from err
    if not callable(factory := getattr(imported, name, None)):
        raise ConfigError(
            f"policy: {spec!r} cannot be loaded ({module!r} has no function {name!r}); "
            "accepted module:factory"
        )
    return factory


def _raised(err: BaseException) -> str:
    """What an exception of the user's code says: its type and its text."""
    return f"{type(err).__name__}: {err}" if str(err) else type(err).__name__
