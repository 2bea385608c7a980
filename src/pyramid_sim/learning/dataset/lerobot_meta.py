"""LeRobot's dataset metadata, v3.0, kept as each episode lands, at a cost that does not grow
with the episodes before it: `meta/info.json` (totals), `meta/stats.json` (the running
aggregate, merged with the new episode's), `meta/tasks.parquet`, and the episode's row in
`meta/episodes/chunk-C/file-F.parquet` (a file per `EPISODES_PER_FILE` episodes, so a landing
rewrites one small file). Each file is written under a temporary name and renamed.

What pyramid_sim says of a recording beyond lerobot's keys lives under `meta/pyramid_sim/`,
where lerobot does not look (an extra key in info.json makes lerobot warn and drop it).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

from ...output.files import write_atomic
from .lerobot_format import (
    CHUNK_SIZE,
    CODEBASE_VERSION,
    DATA_PATH,
    INDEX_FEATURES,
    VIDEO_PATH,
    Feature,
)

EPISODES_PER_FILE = 100  # rows of meta/episodes a file holds
EPISODES_FILE = "meta/episodes/chunk-{chunk_index:03d}/file-{file_index:03d}.parquet"
DATA_FILES_SIZE_IN_MB = 100  # lerobot's defaults: what its writer fills a file up to
VIDEO_FILES_SIZE_IN_MB = 200
# meta/tasks.parquet's columns as pandas' metadata names them: name, pandas' type, numpy's
TASK_COLUMNS = (("task_index", "int64", "int64"), ("task", "unicode", "object"))


def merge_stats(
    total: dict[str, dict[str, Any]] | None, episode: dict[str, dict[str, Any]]
) -> dict[str, dict[str, np.ndarray]]:
    """The statistics of the frames behind `total` and `episode` together: counts add up,
    means and variances pool, extremes extend, and quantiles widen to the envelope of the
    two (lower quantiles the least, upper the greatest), as lerobot's aggregate does after
    0.6.1 (0.6.1 averaged them): exact quantiles cannot be had from summaries."""
    merged: dict[str, dict[str, np.ndarray]] = {}
    for key, part in episode.items():
        b = {k: np.asarray(v, dtype=np.float64) for k, v in part.items()}
        if total is None or key not in total:
            merged[key] = b
            continue
        a = {k: np.asarray(v, dtype=np.float64) for k, v in total[key].items()}
        n_a, n_b = float(a["count"].reshape(-1)[0]), float(b["count"].reshape(-1)[0])
        n = n_a + n_b
        mean = (n_a * a["mean"] + n_b * b["mean"]) / n
        var = (
            n_a * (a["std"] ** 2 + (a["mean"] - mean) ** 2)
            + n_b * (b["std"] ** 2 + (b["mean"] - mean) ** 2)
        ) / n
        doc = {
            "min": np.minimum(a["min"], b["min"]),
            "max": np.maximum(a["max"], b["max"]),
            "mean": mean,
            "std": np.sqrt(var),
            "count": np.array([n]),
        }
        for name in (k for k in b if k.startswith("q") and k[1:].isdigit()):
            pick = np.minimum if int(name[1:]) <= 50 else np.maximum
            doc[name] = pick(a[name], b[name])
        merged[key] = doc
    return merged


def aggregate(rows: list[dict[str, Any]]) -> dict[str, dict[str, np.ndarray]]:
    """The dataset's statistics from its episodes' rows, merged in episode order."""
    total: dict[str, dict[str, np.ndarray]] | None = None
    for row in sorted(rows, key=lambda r: r["episode_index"]):
        total = merge_stats(total, row["stats"])
    return total or {}


def stats_document(stats: dict[str, dict[str, np.ndarray]]) -> dict[str, dict[str, list]]:
    """stats.json's form: lists, counts whole numbers."""
    doc = {}
    for key, part in stats.items():
        doc[key] = {k: np.asarray(v).tolist() for k, v in part.items()}
        doc[key]["count"] = [int(round(float(np.asarray(part["count"]).reshape(-1)[0])))]
    return doc


def episodes_location(episode: int) -> tuple[int, int]:
    """The chunk and file of meta/episodes that hold an episode's row."""
    return divmod(episode // EPISODES_PER_FILE, CHUNK_SIZE)


def write_info(
    root: Path,
    episodes: int,
    frames: int,
    fps: int,
    robot_type: str,
    features: dict[str, Feature],
) -> None:
    """info.json: lerobot's keys only, the totals as of now."""
    info = {
        "codebase_version": CODEBASE_VERSION,
        "robot_type": robot_type,
        "total_episodes": episodes,
        "total_frames": frames,
        "total_tasks": 1,
        "chunks_size": CHUNK_SIZE,
        "data_files_size_in_mb": DATA_FILES_SIZE_IN_MB,
        "video_files_size_in_mb": VIDEO_FILES_SIZE_IN_MB,
        "fps": fps,
        "splits": {"train": f"0:{episodes}"},
        "data_path": DATA_PATH,
        "video_path": VIDEO_PATH,
        "features": {**{k: f.info(fps) for k, f in features.items()}, **INDEX_FEATURES},
    }
    _write_json(root / "meta/info.json", info)


def write_stats(root: Path, stats: dict[str, dict[str, np.ndarray]]) -> None:
    _write_json(root / "meta/stats.json", stats_document(stats))


def write_tasks(root: Path, task: str) -> None:
    """One task, its text the table's index, as lerobot's reader (pandas) finds it: the
    schema's pandas metadata names the index column, and nothing more."""
    table = pa.table({"task_index": pa.array([0], type=pa.int64()), "task": [task]})
    pandas_meta = {
        "index_columns": ["task"],
        "column_indexes": [],
        "columns": [_column(*c) for c in TASK_COLUMNS],
    }
    table = table.replace_schema_metadata({b"pandas": json.dumps(pandas_meta).encode()})
    write_atomic(root / "meta/tasks.parquet", lambda tmp: pq.write_table(table, tmp), ".part")


def _column(name: str, pandas_type: str, numpy_type: str) -> dict[str, Any]:
    """A column as pandas' schema metadata describes it."""
    return {
        "name": name,
        "field_name": name,
        "pandas_type": pandas_type,
        "numpy_type": numpy_type,
        "metadata": None,
    }


def write_episodes_file(root: Path, rows: list[dict[str, Any]], task: str) -> None:
    """The meta/episodes file holding `rows` (every row of that file, in episode order)."""
    rows = sorted(rows, key=lambda r: r["episode_index"])
    chunk, file = episodes_location(rows[0]["episode_index"])
    assert all(episodes_location(r["episode_index"]) == (chunk, file) for r in rows)
    columns: dict[str, list] = {"episode_index": [], "tasks": [], "length": []}
    for row in rows:
        flat = {k: v for k, v in row.items() if k != "stats"}
        flat["tasks"] = [task]
        flat["meta/episodes/chunk_index"], flat["meta/episodes/file_index"] = chunk, file
        for key, stat in row["stats"].items():
            for name, value in stat.items():
                flat[f"stats/{key}/{name}"] = (
                    np.asarray(value, dtype=np.float64).reshape(-1).tolist()
                )
        for key, value in flat.items():
            columns.setdefault(key, []).append(value)
    table = pa.table(columns)
    path = root / EPISODES_FILE.format(chunk_index=chunk, file_index=file)
    write_atomic(path, lambda tmp: pq.write_table(table, tmp), ".part")


def rows_in(path: Path) -> int:
    """How many rows a parquet file holds (from its footer)."""
    return int(pq.read_metadata(path).num_rows)


def _write_json(path: Path, document: dict[str, Any]) -> None:
    text = json.dumps(document, indent=4) + "\n"
    write_atomic(path, lambda tmp: tmp.write_text(text), ".part")
