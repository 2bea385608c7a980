"""Where jobs run, checked before anything runs: worker processes here, or Ray tasks (on a
Ray started here or a cluster). Sweeps and recordings take the same backends."""

from __future__ import annotations

import importlib.util

from ..choices import BACKENDS
from ..errors import ConfigError, MachineError


def check_backend(backend: str, ray_address: str | None) -> None:
    """ConfigError for an unknown backend, or a Ray address without Ray; MachineError for Ray
    when it is not installed."""
    if backend not in BACKENDS:
        raise ConfigError(f"backend: unknown {backend!r}; accepted {', '.join(BACKENDS)}")
    if ray_address is not None and backend != "ray":
        raise ConfigError("ray address: only with --backend ray")
    if backend == "ray":
        require_ray()


def require_ray() -> None:
    """MachineError when the ray extra is not installed."""
    if importlib.util.find_spec("ray") is None:
        raise MachineError(
            "backend: ray is not installed; accepted process, or ray after pip install -e '.[ray]'"
        )
