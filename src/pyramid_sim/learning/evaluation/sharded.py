"""An evaluation's episodes split across worker processes or Ray tasks, each worker with its
own environment and policy: an episode depends on its seed alone, so the rows are those one
worker makes, bit for bit."""

from __future__ import annotations

import tempfile
from collections.abc import Callable
from contextlib import closing
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ...errors import PolicyError, PyramidSimError
from ...jobs.runner import run_jobs
from ...output.files import atomic_path
from ...output.replay_tape import episode_name
from .config import EvaluateConfig
from .episodes import episode_row, make_env
from .policies import make_policy

_WORKER: dict[str, Any] = {}  # this worker process's evaluation, environment and policy


@dataclass(frozen=True)
class _EpisodeAway:
    """One episode run in a worker process or a Ray task: its row, its replay's bytes, and
    its film's where it is among the first filmed (the evaluation's machine writes the files,
    so a Ray node needs no disk shared with it). A policy's error is handed back, not
    raised: it is the user's, and is said in one line."""

    config: EvaluateConfig

    def __call__(self, i: int) -> dict[str, Any]:
        if _WORKER.get("config") != self.config:
            if "env" in _WORKER:
                _WORKER.pop("env").close()
            env = make_env(self.config)
            _WORKER.update(config=self.config, env=env, policy=make_policy(self.config.policy, env))
        env, policy = _WORKER["env"], _WORKER["policy"]
        try:
            with tempfile.TemporaryDirectory(prefix="pyramid-sim-film-") as tmp:
                film = Path(tmp) / "episode.mp4" if i < self.config.videos else None
                replay = Path(tmp) / "replay" / "episode.npz"
                row = episode_row(env, policy, self.config, i, None, film, replay)
                meshes = {p.name: p.read_bytes() for p in replay.parent.glob("meshes_*.npz")}
                value = {"row": row, "replay": replay.read_bytes(), "meshes": meshes}
                return {**value, "film": film.read_bytes()} if film is not None else value
        except PolicyError as err:
            return {"policy_error": str(err)}


def run_sharded(
    config: EvaluateConfig,
    out: Path | None,
    on_episode: Callable[[dict[str, Any]], Any] | None,
    replays: Path | None = None,
) -> list[dict[str, Any]]:
    """The episodes' rows in seed order, run by the job runner on `config.workers` processes
    or Ray tasks; `on_episode` hears each as it ends; their poses written into `replays`. A worker's crash or a policy's error
    stops the evaluation (PyramidSimError, PolicyError), its films unwritten."""
    ends = run_jobs(
        _EpisodeAway(config),
        range(config.episodes),
        workers=config.workers,
        backend=config.backend,
        address=config.ray_address,
        warm=("pyramid_sim.learning.evaluation.sharded",),
    )
    done: dict[int, dict[str, Any]] = {}
    with closing(ends):  # an interrupt, or a failure, stops every worker at once
        for end in ends:
            if end.failure is not None:
                seed = config.first_seed + end.job
                raise PyramidSimError(f"episode {end.job + 1} (seed {seed}): {end.failure}")
            if "policy_error" in end.value:
                raise PolicyError(end.value["policy_error"])
            done[end.job] = end.value
            if on_episode is not None:
                on_episode(end.value["row"])
    if replays is not None:
        for i, value in sorted(done.items()):
            (replays / episode_name(i)).write_bytes(value["replay"])
            for name, data in value["meshes"].items():  # the episodes' shared meshes, once
                if not (replays / name).exists():
                    (replays / name).write_bytes(data)
    if out is not None:
        for i, value in sorted(done.items()):
            if "film" in value:
                seed = config.first_seed + i
                with atomic_path(out / f"episode_{seed}.mp4") as tmp:
                    tmp.write_bytes(value["film"])
    return [done[i]["row"] for i in range(config.episodes)]
