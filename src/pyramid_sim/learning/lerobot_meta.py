"""LeRobot's dataset metadata, v3.0: `meta/info.json`, `meta/stats.json`, `meta/tasks.parquet`
and `meta/episodes/chunk-000/file-000.parquet`, rebuilt whole from the finished episodes' rows
(each file under a temporary name, then renamed)."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

from .lerobot_format import (
    CHUNK_SIZE,
    CODEBASE_VERSION,
    DATA_PATH,
    EPISODES_PATH,
    INDEX_FEATURES,
    QUANTILES,
    VIDEO_PATH,
    Feature,
)


def aggregate(rows: list[dict[str, Any]]) -> dict[str, dict[str, list]]:
    """The dataset's statistics from its episodes': counts add up, means and variances pool,
    extremes extend; quantiles are the frame-weighted mean of the episodes' (approximate, as
    lerobot's own aggregate)."""
    out: dict[str, dict[str, list]] = {}
    for key in rows[0]["stats"]:
        parts = [r["stats"][key] for r in rows]
        counts = np.array([float(p["count"][0]) for p in parts])
        weights = (counts / counts.sum()).reshape(-1, *([1] * np.ndim(parts[0]["mean"])))
        means = np.stack([p["mean"] for p in parts])
        mean = (weights * means).sum(axis=0)
        var = (weights * (np.stack([p["std"] for p in parts]) ** 2 + (means - mean) ** 2)).sum(
            axis=0
        )
        doc = {
            "min": np.min([p["min"] for p in parts], axis=0),
            "max": np.max([p["max"] for p in parts], axis=0),
            "mean": mean,
            "std": np.sqrt(var),
            "count": np.array([int(counts.sum())]),
        }
        for q in QUANTILES:
            name = f"q{int(q * 100):02d}"
            doc[name] = (weights * np.stack([p[name] for p in parts])).sum(axis=0)
        out[key] = {k: np.asarray(v).tolist() for k, v in doc.items()}
    return out


def write_meta(
    root: Path,
    rows: list[dict[str, Any]],
    fps: int,
    robot_type: str,
    features: dict[str, Feature],
    task: str,
    extra: dict[str, Any],
) -> None:
    """info.json, stats.json, tasks.parquet and the episodes' table for the finished episodes
    `rows` (in episode order), each file written whole."""
    rows = sorted(rows, key=lambda r: r["episode_index"])
    frames = sum(r["length"] for r in rows)
    info = {
        "codebase_version": CODEBASE_VERSION,
        "robot_type": robot_type,
        "total_episodes": len(rows),
        "total_frames": frames,
        "total_tasks": 1,
        "chunks_size": CHUNK_SIZE,
        "data_files_size_in_mb": 100,
        "video_files_size_in_mb": 200,
        "fps": fps,
        "splits": {"train": f"0:{len(rows)}"},
        "data_path": DATA_PATH,
        "video_path": VIDEO_PATH,
        "features": {**{k: f.info(fps) for k, f in features.items()}, **INDEX_FEATURES},
        **extra,
    }
    _write(root / "meta/info.json", (json.dumps(info, indent=4) + "\n").encode())
    if rows:
        stats = aggregate(rows)
        _write(root / "meta/stats.json", (json.dumps(stats, indent=4) + "\n").encode())
    _write_parquet(root / "meta/tasks.parquet", _tasks_table(task))
    _write_parquet(root / EPISODES_PATH, _episodes_table(rows, task))


def _tasks_table(task: str) -> pa.Table:
    """One task, its text the table's index (as pandas writes lerobot's task table)."""
    table = pa.table({"task_index": pa.array([0], type=pa.int64()), "task": [task]})
    pandas_meta = {
        "index_columns": ["task"],
        "column_indexes": [],
        "columns": [
            {
                "name": "task_index",
                "field_name": "task_index",
                "pandas_type": "int64",
                "numpy_type": "int64",
                "metadata": None,
            },
            {
                "name": "task",
                "field_name": "task",
                "pandas_type": "unicode",
                "numpy_type": "object",
                "metadata": None,
            },
        ],
        "creator": {"library": "pyarrow", "version": pa.__version__},
        "pandas_version": "2.2.3",
    }
    return table.replace_schema_metadata({b"pandas": json.dumps(pandas_meta).encode()})


def _episodes_table(rows: list[dict[str, Any]], task: str) -> pa.Table:
    columns: dict[str, list] = {"episode_index": [], "tasks": [], "length": []}
    for row in rows:
        flat = {k: v for k, v in row.items() if k != "stats"}
        flat["tasks"] = [task]
        flat["meta/episodes/chunk_index"], flat["meta/episodes/file_index"] = 0, 0
        for key, stat in row["stats"].items():
            for name, value in stat.items():
                flat[f"stats/{key}/{name}"] = (
                    np.asarray(value, dtype=np.float64).reshape(-1).tolist()
                )
        for key, value in flat.items():
            columns.setdefault(key, []).append(value)
    return pa.table(columns) if rows else pa.table({k: pa.array([], pa.int64()) for k in columns})


def _write(path: Path, data: bytes) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.part")
    tmp.write_bytes(data)
    os.replace(tmp, path)


def _write_parquet(path: Path, table: pa.Table) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.part")
    pq.write_table(table, tmp)
    os.replace(tmp, path)
