"""Episodes filmed as Ray tasks, on this machine or across a cluster. A task films its episode
into a temporary folder on its own node and hands the files back, so the dataset's machine
needs no disk shared with the nodes: the files are written into the episode's staging folder
here and land as a local worker's would."""

from __future__ import annotations

import tempfile
from collections import deque
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import Any

from .staging import film_in_worker, staging_folder


def film_shipped(config: Any, episode: int) -> dict[str, Any]:
    """A Ray task: one episode filmed on its node, its staged files' bytes by relative path."""
    with tempfile.TemporaryDirectory(prefix="pyramid-sim-episode-") as tmp:
        result = film_in_worker(config, episode, Path(tmp))
        root = staging_folder(Path(tmp), episode)
        result["files"] = {
            str(path.relative_to(root)): path.read_bytes()
            for path in sorted(root.rglob("*"))
            if path.is_file()
        }
    return result


def _unpack(out: Path, result: dict[str, Any]) -> dict[str, Any]:
    """Write a shipped episode's files into its staging folder here; its result, files gone."""
    root = staging_folder(out, result["episode"])
    for name, content in result.pop("files").items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(content)
    return result


def ray_staged(
    config: Any, episodes: Iterable[int], out: Path, workers: int, address: str | None
) -> Iterator[dict[str, Any]]:
    """The episodes filmed as Ray tasks, at most `workers` at once, yielded in episode order
    once each is staged here."""
    from ..sweep.ray_backend import ray_session

    order = list(episodes)
    pending = deque(order)
    with ray_session(address, workers) as ray:
        task = ray.remote(num_cpus=1, max_retries=0)(film_shipped)
        running: dict[Any, int] = {}
        done: dict[int, dict[str, Any]] = {}
        try:
            for episode in order:
                while episode not in done:
                    while pending and len(running) < workers:
                        e = pending.popleft()
                        running[task.remote(config, e)] = e
                    ready, _ = ray.wait(list(running), num_returns=1)
                    for ref in ready:
                        done[running.pop(ref)] = _unpack(out, ray.get(ref))
                yield done.pop(episode)
        finally:
            for ref in running:
                ray.cancel(ref, force=True)
