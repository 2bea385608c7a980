"""`pyramid-sim record`: the scripted expert's builds as a LeRobot dataset (v3.0).

An episode is one whole build from its seed (`first_seed + episode`), kept at `fps` with the
cameras asked for. Re-running adds only the episodes missing; an episode is in the dataset
once its files and its record (`meta/pyramid_sim/episode_NNNNNN.json`: its seed, success and
result.json) are in place, which happens together, Ctrl-C and SIGTERM held for that moment.
Resuming refuses a folder recorded with other settings, since they shape the files, a folder
holding anything else, and an episode whose files are damaged unless asked to record it again
(resume_checks.py).
"""

from __future__ import annotations

import json
import re
import shutil
from bisect import bisect_left
from collections.abc import Callable
from contextlib import closing
from pathlib import Path
from typing import Any

from ...output.files import write_atomic
from ...output.video import signals_held
from ...version import __version__
from ..dataset import lerobot_format as fmt
from ..dataset import lerobot_meta as meta
from ..env.env import BuildEnv
from ..task.layout import camera_names, check_cameras
from ..task.observation_names import OBSERVED
from ..task.variation import check_differ
from .episode import PRIMITIVES, task_text
from .filming import FilmAway, PolicyMaker, features, film_staged, learner_for, make_env
from .record_config import RecordConfig, Recorded
from .resume_checks import (
    RECORDS,
    check_folder,
    check_resumable,
    damaged_episodes,
    description_problem,
    forget,
    read_records,
    refusal,
)
from .same_recording import check_same_recording, settings_of
from .staging import STAGING, land, staged

__all__ = ["RecordConfig", "Recorded", "record"]

DATASET_DOC = f"{RECORDS}/dataset.json"


def _clear_unrecorded(root: Path, recorded: set[int]) -> None:
    """Files of an episode that never made it into the dataset (a run killed outright, or
    halfway through writing), and the dataset's temporary files, go; files of other names
    are not the dataset's and stay."""
    for path in [*root.glob("data/chunk-*/*"), *root.glob("videos/*/chunk-*/*")]:
        if re.fullmatch(r"\.file-\d{3}\..*\.part", path.name):
            path.unlink()
            continue
        chunk, file = (
            re.fullmatch(r"chunk-(\d{3})", path.parent.name),
            re.fullmatch(r"file-(\d{3})\.(parquet|mp4)", path.name),
        )
        if chunk and file and int(chunk[1]) * fmt.CHUNK_SIZE + int(file[1]) not in recorded:
            path.unlink()
    shutil.rmtree(root / STAGING, ignore_errors=True)


def record(
    out: Path,
    config: RecordConfig,
    on_frame: Callable[[int, int], Any] | None = None,
    on_episode: Callable[[int], Any] | None = None,
    policies: PolicyMaker | None = None,
    repair: bool = False,
) -> Recorded:
    """Record the episodes `out` lacks (and with `repair` those whose files are damaged);
    `on_frame(episode, its frames so far)` after each frame (with workers, once an episode
    lands, with all its frames); `on_episode(episodes in the dataset)` before the first is
    filmed and after each lands. A DAgger round's learner (`config.policy`) is made by
    `policies(policy, env)`, in each worker."""
    records = _resumable(out, config, repair)  # before the scene is compiled
    env = make_env(config)
    try:
        check_cameras(config.cameras, env.config.robot_description)
        check_differ(
            config.episodes, config.variation, config.randomize, env.config.layout.spawn_jitter_mm
        )
        learner = learner_for(env, config, policies)  # a bad policy refused before filming
        _clear_unrecorded(out, set(records))
        dataset = _Landing(out, env, config, records)
        missing = [e for e in range(config.episodes) if e not in records]
        parallel = config.workers > 1 or config.backend == "ray"
        if on_episode is not None:
            on_episode(len(records))

        def film_here(episode: int) -> dict[str, Any]:
            return film_staged(env, config, episode, out, on_frame, learner)

        episodes = staged(
            missing,
            out,
            film_here,
            FilmAway(config, policies),
            workers=config.workers,
            backend=config.backend,
            address=config.ray_address,
            warm=("pyramid_sim.learning.recording.filming",),  # MuJoCo, mink and the environment
        )
        with closing(episodes):  # an interrupt stops every worker at once
            for result in episodes:
                if parallel and on_frame is not None:
                    on_frame(result["episode"], result["row"]["length"])
                with signals_held():  # the files and the record land together
                    dataset.land(result)
                if on_episode is not None:
                    on_episode(len(records))
    finally:
        env.close()
        shutil.rmtree(out / STAGING, ignore_errors=True)
    failed = tuple(sorted(i for i, r in records.items() if not r["success"]))
    return Recorded(out, len(records), dataset.frames_before.total, dataset.added, failed)


def _resumable(out: Path, config: RecordConfig, repair: bool) -> dict[int, dict[str, Any]]:
    """The episodes `out` holds that this run keeps: ConfigError for a folder holding what no
    recording of these settings wrote, or a damaged episode unless `repair` (it is forgotten,
    to be recorded again)."""
    records, damaged = read_records(out)
    check_folder(out, bool(records or damaged))
    check_same_recording(out, records, config)
    damaged.update(damaged_episodes(out, records))
    if damaged and not repair:
        raise refusal(out, damaged)
    check_resumable(out, records, damaged, config.episodes, config.policy, repair)
    forget(out, damaged)
    return {i: r for i, r in records.items() if i not in damaged}


class _Landing:
    """The dataset as episodes land: each landing writes the episode's files and record, and
    updates the metadata at a cost that does not grow with the episodes before it."""

    def __init__(
        self, out: Path, env: BuildEnv, config: RecordConfig, records: dict[int, dict[str, Any]]
    ) -> None:
        self.out, self.env, self.config, self.records = out, env, config, records
        self.features = features(env, config)
        self.task = task_text(env)
        self.robot_type = env.lerobot_units.robot_type
        rows = [r["row"] for r in records.values()]
        self.stats = meta.aggregate(rows) if rows else None
        self.frames_before = _FramesBefore({i: r["row"]["length"] for i, r in records.items()})
        self.groups: dict[tuple[int, int], dict[int, dict[str, Any]]] = {}
        for index, rec in records.items():
            self.groups.setdefault(meta.episodes_location(index), {})[index] = rec["row"]
        self.added = 0
        if records:
            self._repair()
            if description_problem(out):  # only with repair: refused otherwise
                _write_text(out / DATASET_DOC, json.dumps(_dataset_doc(env, config), indent=1))

    def _repair(self) -> None:
        """The metadata of the episodes already in the dataset, written again where a run
        killed between an episode's record and its metadata left it short: once a run, and
        a meta/episodes file only if its rows are not its episodes'."""
        out, config = self.out, self.config
        for (chunk, file), rows in self.groups.items():
            path = out / meta.EPISODES_FILE.format(chunk_index=chunk, file_index=file)
            if not path.exists() or meta.rows_in(path) != len(rows):
                meta.write_episodes_file(out, list(rows.values()), self.task)
        if self.stats is not None:
            meta.write_stats(out, self.stats)
        meta.write_info(
            out,
            len(self.records),
            self.frames_before.total,
            config.fps,
            self.robot_type,
            self.features,
        )

    def land(self, result: dict[str, Any]) -> None:
        out, config, episode, end = self.out, self.config, result["episode"], result["end"]
        row = land(out, result, self.frames_before(episode))
        self.frames_before.add(episode, row["length"])
        self.records[episode] = record = {
            "episode_index": episode,
            "seed": config.first_seed + episode,
            "task": self.task,
            "fps": config.fps,
            "features": list(self.features),
            "success": end.success,
            "failure": end.failure,
            "randomization": result["randomization"],
            "result": end.result,
            "config": settings_of(config),
            "row": _jsonable(row),
        }
        if config.policy is not None:  # DAgger: what drove it, and how much of it
            record["driver"] = {
                "policy": config.policy,
                "beta": config.beta,
                "learner_steps": end.learner_steps,
            }
            if config.takeover is not None:  # HG-DAgger's gate, and how often it closed
                record["driver"].update(takeover=config.takeover, takeovers=end.takeovers)
        _write_text(out / RECORDS / f"episode_{episode:06d}.json", json.dumps(record, indent=1))
        if self.added == 0:  # this run's first: the files every episode shares
            meta.write_tasks(out, self.task)
            _write_text(out / DATASET_DOC, json.dumps(_dataset_doc(self.env, config), indent=1))
        self.stats = meta.merge_stats(self.stats, row["stats"])
        meta.write_stats(out, self.stats)
        group = self.groups.setdefault(meta.episodes_location(episode), {})
        group[episode] = record["row"]
        meta.write_episodes_file(out, list(group.values()), self.task)
        meta.write_info(
            out,
            len(self.records),
            self.frames_before.total,
            config.fps,
            self.robot_type,
            self.features,
        )
        self.added += 1


class _FramesBefore:
    """How many frames the dataset holds before an episode, kept as episodes land (each
    answer costs no more than the episodes landed since the last)."""

    def __init__(self, lengths: dict[int, int]) -> None:
        self.lengths = dict(lengths)
        self.order = sorted(lengths)
        self.total = sum(lengths.values())

    def __call__(self, episode: int) -> int:
        at = bisect_left(self.order, episode)
        after = sum(self.lengths[i] for i in self.order[at:])  # none, landing in order
        return self.total - after

    def add(self, episode: int, length: int) -> None:
        self.order.insert(bisect_left(self.order, episode), episode)
        self.lengths[episode] = length
        self.total += length


def _dataset_doc(env: BuildEnv, config: RecordConfig) -> dict[str, Any]:
    """What pyramid_sim says of the recording beyond lerobot's keys (meta/pyramid_sim/)."""
    spec = env.plan.spec
    named = camera_names(env.config.robot_description)
    doc = {
        "version": __version__,
        "lerobot_version": fmt.LEROBOT_VERSION,
        "structure": spec.name,
        "size": dict(spec.size),
        "primitives": list(PRIMITIVES),
        "first_seed": config.first_seed,
        "variation": config.variation,
        "randomize": list(env.randomize),
        "limit_commands": config.limit_commands,
        "action_mode": config.action_mode,
        "linger": config.linger,
        "cameras": {c: n for c, n in named.items() if c in config.cameras},
    }
    for hidden in OBSERVED:  # said only where the observation leaves it out
        if not getattr(config, hidden):
            doc[hidden] = False
    return doc


def _write_text(path: Path, text: str) -> None:
    write_atomic(path, lambda tmp: tmp.write_text(text + "\n"))


def _jsonable(row: dict[str, Any]) -> dict[str, Any]:
    import numpy as np

    def convert(value: Any) -> Any:
        if isinstance(value, dict):
            return {k: convert(v) for k, v in value.items()}
        if isinstance(value, np.ndarray):
            return value.tolist()
        if isinstance(value, np.generic):
            return value.item()
        return value

    return convert(row)
