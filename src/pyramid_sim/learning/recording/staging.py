"""Episodes filmed apart and landed in order: each is written into a staging folder of its
own (in this process, in a worker process, or in a Ray task on any node), its frames indexed
from 0; landing moves its files into the dataset and shifts its frames' dataset-wide index to
where it falls, so episodes filmed in parallel make the dataset a serial run would.

The stager knows nothing of what an episode is: it is handed the function that films one.
"""

from __future__ import annotations

import shutil
import tempfile
from collections.abc import Callable, Generator, Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

from ...errors import PyramidSimError
from ...jobs.runner import run_jobs
from ...output.files import atomic_path, move_into_place
from ...output.replay_tape import EPISODES_FOLDER
from ..dataset import lerobot_format as fmt

STAGING = ".staging"
# The films: here, an episode and the progress callback; away (a picklable callable), an
# episode and the folder whose staging area it is filmed into. Each returns the episode's result.
FilmHere = Callable[[int], dict[str, Any]]
FilmAway = Callable[[int, Path], dict[str, Any]]


def staging_folder(out: Path, episode: int) -> Path:
    return out / STAGING / f"episode_{episode:06d}"


REFUSED = "refused"  # a worker's result key: the ConfigError its episode raised


@dataclass(frozen=True)
class _FilmInto:
    """A worker's job: film an episode into `out`'s staging area (a folder this machine
    shares with its worker processes)."""

    film: FilmAway
    out: Path

    def __call__(self, episode: int) -> dict[str, Any]:
        return self.film(episode, self.out)


@dataclass(frozen=True)
class _FilmShipped:
    """A Ray task's job: film an episode into a temporary folder on its own node and hand back
    its staged files' bytes, so the dataset's machine needs no disk shared with the nodes."""

    film: FilmAway

    def __call__(self, episode: int) -> dict[str, Any]:
        with tempfile.TemporaryDirectory(prefix="pyramid-sim-episode-") as tmp:
            result = self.film(episode, Path(tmp))
            if REFUSED in result:
                return result
            root = staging_folder(Path(tmp), episode)
            result["files"] = {
                str(path.relative_to(root)): path.read_bytes()
                for path in sorted(root.rglob("*"))
                if path.is_file()
            }
        return result


def _unpack(out: Path, result: dict[str, Any]) -> dict[str, Any]:
    """A shipped episode's files written into its staging folder here; its result, files gone."""
    root = staging_folder(out, result["episode"])
    for name, content in result.pop("files").items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(content)
    return result


def staged(
    episodes: Iterable[int],
    out: Path,
    film_here: FilmHere,
    film_away: FilmAway,
    *,
    workers: int = 1,
    backend: str = "process",
    address: str | None = None,
    warm: tuple[str, ...] = (),
) -> Generator[dict[str, Any], None, None]:
    """The episodes filmed, yielded in episode order: here one after another, or by the job
    runner on `workers` processes (importing the modules `warm` names before their first) or
    Ray tasks (`backend`, on the cluster at `address`). An episode whose worker crashed raises
    PyramidSimError naming it, after those before it."""
    todo = list(episodes)
    if backend != "ray" and workers <= 1:
        for episode in todo:
            yield film_here(episode)
        return
    ray = backend == "ray"
    work = _FilmShipped(film_away) if ray else _FilmInto(film_away, out)
    ends = run_jobs(
        work,
        todo,
        workers=workers,
        backend=backend,
        address=address,
        warm=warm,
    )
    done: dict[int, Any] = {}
    try:
        for episode in todo:
            while episode not in done:
                end = next(ends)
                done[end.job] = end
            end = done.pop(episode)
            if end.failure is not None:
                raise PyramidSimError(f"episode {episode}: {end.failure}")
            if REFUSED in end.value:  # a policy's error in a worker: as in one process
                raise end.value[REFUSED]
            yield _unpack(out, end.value) if ray else end.value
    finally:
        ends.close()  # an interrupt, or a failure, stops every worker at once


def land(out: Path, result: dict[str, Any], first: int) -> dict[str, Any]:
    """Move a staged episode's files into the dataset, its frames' index starting at
    `first`; its row, placed."""
    episode, row = result["episode"], dict(result["row"])
    root = staging_folder(out, episode)
    chunk, file = fmt.location(episode)
    data = fmt.DATA_PATH.format(chunk_index=chunk, file_index=file)
    table = pq.read_table(root / data)
    index = table.column("index").to_numpy() + first
    table = table.set_column(
        table.schema.get_field_index("index"), "index", pa.array(index, type=pa.int64())
    )
    with atomic_path(out / data, suffix=".part") as tmp:
        pq.write_table(table, tmp, compression="snappy")
    for video in root.glob("videos/*/*/*.mp4"):
        move_into_place(video, out / video.relative_to(root))
    for taped in sorted(root.glob(f"{EPISODES_FOLDER}/*.npz")):  # its poses, for a replay
        if taped.name.startswith("episode_") or not (out / taped.relative_to(root)).exists():
            move_into_place(taped, out / taped.relative_to(root))
    shutil.rmtree(root, ignore_errors=True)
    row["dataset_from_index"], row["dataset_to_index"] = first, first + row["length"]
    stats = dict(row["stats"])
    stats["index"] = {
        k: (v if k in ("std", "count") else np.asarray(v) + first)
        for k, v in stats["index"].items()
    }
    row["stats"] = stats
    return row
