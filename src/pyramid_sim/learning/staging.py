"""Episodes filmed apart and landed in order: each is written into a staging folder of its
own (in this process or in a worker's), its frames indexed from 0; landing moves its files
into the dataset and shifts its frames' dataset-wide index to where it falls, so episodes
filmed in parallel make the dataset a serial run would."""

from __future__ import annotations

import multiprocessing
import os
import shutil
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from pathlib import Path
from typing import Any

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

from . import lerobot_format as fmt

STAGING = ".staging"
OnFrame = Callable[[int, int], Any]


def staging_folder(out: Path, episode: int) -> Path:
    return out / STAGING / f"episode_{episode:06d}"


def film_staged(
    config: Any, env: Any, episode: int, out: Path, on_frame: OnFrame | None = None
) -> dict[str, Any]:
    """Film one episode into its staging folder: how it ended, its draw and its row (frames
    indexed from 0)."""
    from .record import features, film_episode

    root = staging_folder(out, episode)
    shutil.rmtree(root, ignore_errors=True)
    files = fmt.EpisodeFiles(root, episode, config.fps, features(env, config))
    end, row = film_episode(env, files, config, on_frame)
    files.commit()  # into the staging folder: the dataset sees nothing yet
    return {"episode": episode, "end": end, "randomization": env.drawn, "row": row}


_WORKER_ENV: dict[str, Any] = {}


def film_in_worker(config: Any, episode: int, out: Path) -> dict[str, Any]:
    """A worker process's episode (a pool's or Ray's), its environment made once per process."""
    from .record import make_env

    if "env" not in _WORKER_ENV:
        os.environ.setdefault("OMP_NUM_THREADS", "1")
        _WORKER_ENV["env"] = make_env(config)
    return film_staged(config, _WORKER_ENV["env"], episode, out)


def staged(
    config: Any,
    env: Any,
    episodes: Iterable[int],
    out: Path,
    workers: int,
    on_frame: OnFrame | None = None,
) -> Iterator[dict[str, Any]]:
    """The episodes filmed, yielded in episode order: here one after another, or on
    `workers` processes or Ray tasks (`config.backend`; each frame's progress is then told
    only when its episode lands)."""
    todo = list(episodes)
    if config.backend == "ray":
        from .ray_staging import ray_staged

        for result in ray_staged(config, todo, out, workers, config.ray_address):
            if on_frame is not None:
                on_frame(result["episode"], result["row"]["length"])
            yield result
        return
    if workers <= 1:
        for episode in todo:
            yield film_staged(config, env, episode, out, on_frame)
        return
    context = multiprocessing.get_context("spawn")  # no GL or MuJoCo state forked
    with ProcessPoolExecutor(max_workers=workers, mp_context=context) as pool:
        running = {pool.submit(film_in_worker, config, e, out): e for e in todo}
        done: dict[int, dict[str, Any]] = {}
        try:
            for episode in todo:
                while episode not in done:
                    finished, _ = wait(running, return_when=FIRST_COMPLETED)
                    for future in finished:
                        done[running.pop(future)] = future.result()
                result = done.pop(episode)
                if on_frame is not None:
                    on_frame(episode, result["row"]["length"])
                yield result
        except BaseException:
            pool.shutdown(wait=False, cancel_futures=True)
            raise


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
    target = out / data
    target.parent.mkdir(parents=True, exist_ok=True)
    tmp = target.with_name(f".{target.name}.part")
    pq.write_table(table, tmp, compression="snappy")
    os.replace(tmp, target)
    for video in root.glob("videos/*/*/*.mp4"):
        final = out / video.relative_to(root)
        final.parent.mkdir(parents=True, exist_ok=True)
        os.replace(video, final)
    shutil.rmtree(root, ignore_errors=True)
    row["dataset_from_index"], row["dataset_to_index"] = first, first + row["length"]
    stats = dict(row["stats"])
    stats["index"] = {
        k: (v if k in ("std", "count") else np.asarray(v) + first)
        for k, v in stats["index"].items()
    }
    row["stats"] = stats
    return row
