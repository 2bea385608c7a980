"""LeRobot's dataset layout, v3.0, written with pyarrow and PyAV (no torch).

Each episode gets its own data file and its own video file a camera (`chunk-C/file-F`, F the
episode's index within its chunk of 1000), as lerobot's own writer does once a file is full.
An episode's frames are indexed from 0 as it is written; `staging.land` places them in the
dataset. Files are written under temporary names ending in `.part` (no reader's glob sees
them) and renamed into place (output/files.py); the metadata is kept by lerobot_meta.py. A
record killed at any moment leaves the episodes it finished, loadable.

The layout is that of LeRobot's v3.0 datasets as `LEROBOT_VERSION`'s reader and tools read
them (the round trip in .ci/lerobot_round_trip installs that release and trains on a recording).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

from ...output.files import move_into_place, temporary_beside

CODEBASE_VERSION = "v3.0"
LEROBOT_VERSION = "0.6.1"  # the lerobot release whose reader the format is held to
CHUNK_SIZE = 1000  # files a chunk folder, as lerobot's default
DATA_PATH = "data/chunk-{chunk_index:03d}/file-{file_index:03d}.parquet"
VIDEO_PATH = "videos/{video_key}/chunk-{chunk_index:03d}/file-{file_index:03d}.mp4"
QUANTILES = (0.01, 0.10, 0.50, 0.90, 0.99)
STATS_EVERY = 5  # a video's statistics sample every fifth frame, a quarter of its pixels
VIDEO_CODEC = "h264"  # libx264, yuv420p: decoded by PyAV and torchcodec alike
INDEX_FEATURES = {  # what every frame of a LeRobot dataset carries besides its own features
    "timestamp": {"dtype": "float32", "shape": [1], "names": None},
    "frame_index": {"dtype": "int64", "shape": [1], "names": None},
    "episode_index": {"dtype": "int64", "shape": [1], "names": None},
    "index": {"dtype": "int64", "shape": [1], "names": None},
    "task_index": {"dtype": "int64", "shape": [1], "names": None},
}


@dataclass(frozen=True)
class Feature:
    """A per-frame feature: its dtype ("float32", "int64", "bool" or "video"), shape and
    the names of its entries."""

    dtype: str
    shape: tuple[int, ...]
    names: Sequence[str] | None = None

    def info(self, fps: int) -> dict[str, Any]:
        doc: dict[str, Any] = {
            "dtype": self.dtype,
            "shape": list(self.shape),
            "names": list(self.names) if self.names is not None else None,
        }
        if self.dtype == "video":
            height, width, channels = self.shape
            doc["names"] = ["height", "width", "channels"]
            doc["info"] = {
                "video.height": height,
                "video.width": width,
                "video.codec": VIDEO_CODEC,
                "video.pix_fmt": "yuv420p",
                "video.is_depth_map": False,
                "video.fps": fps,
                "video.channels": channels,
                "has_audio": False,
            }
        return doc


def location(episode: int) -> tuple[int, int]:
    """The chunk and file index of an episode's own files."""
    return divmod(episode, CHUNK_SIZE)


@dataclass
class EpisodeFiles:
    """One episode being written: its frames' values gathered, its videos encoded as the
    frames come. `close()` finishes them and returns its metadata row; `commit()` moves the
    files into place."""

    root: Path
    episode: int
    fps: int
    features: dict[str, Feature]
    task_index: int = 0
    values: dict[str, list[Any]] = field(default_factory=dict)
    _videos: dict[str, Any] = field(default_factory=dict)
    _temporary: list[tuple[Path, Path]] = field(default_factory=list)
    _pixels: dict[str, list[np.ndarray]] = field(default_factory=dict)
    _filmed: dict[str, int] = field(default_factory=dict)

    def add(self, frame: dict[str, Any]) -> None:
        """One frame: a value for every feature (an H x W x 3 uint8 image for a video)."""
        for key, feature in self.features.items():
            if feature.dtype == "video":
                self._film(key, frame[key])
            else:
                self.values.setdefault(key, []).append(frame[key])

    def _film(self, key: str, image: np.ndarray) -> None:
        import av

        if key not in self._videos:
            chunk, file = location(self.episode)
            final = self.root / VIDEO_PATH.format(video_key=key, chunk_index=chunk, file_index=file)
            tmp = temporary_beside(final, suffix=".part")
            container = av.open(str(tmp), mode="w", format="mp4")
            stream = container.add_stream("libx264", rate=self.fps)
            stream.width, stream.height = image.shape[1], image.shape[0]
            stream.pix_fmt = "yuv420p"
            stream.options = {"crf": "23", "preset": "veryfast", "g": "2"}
            self._videos[key] = (container, stream)
            self._temporary.append((tmp, final))
            self._pixels[key] = []
        container, stream = self._videos[key]
        video_frame = av.VideoFrame.from_ndarray(np.ascontiguousarray(image), format="rgb24")
        for packet in stream.encode(video_frame):
            container.mux(packet)
        self._filmed[key] = self._filmed.get(key, 0) + 1
        if self._filmed[key] % STATS_EVERY == 1:
            self._pixels[key].append(image[::4, ::4])  # a sample for the statistics

    def close(self) -> dict[str, Any]:
        """Finish the videos and write the frames' table, under temporary names; the
        episode's row of `meta/episodes` (its statistics included). `commit()` moves the
        files into place."""
        length = len(next(iter(self.values.values()))) if self.values else 0
        for container, stream in self._videos.values():
            for packet in stream.encode():
                container.mux(packet)
            container.close()
        chunk, file = location(self.episode)
        data = self.root / DATA_PATH.format(chunk_index=chunk, file_index=file)
        tmp = temporary_beside(data, suffix=".part")
        pq.write_table(self._table(length), tmp, compression="snappy")
        self._temporary.append((tmp, data))
        row: dict[str, Any] = {
            "episode_index": self.episode,
            "length": length,
            "data/chunk_index": chunk,
            "data/file_index": file,
            "dataset_from_index": 0,  # its frames from 0: landing places them (staging.land)
            "dataset_to_index": length,
        }
        for key in self._videos:
            row.update(
                {
                    f"videos/{key}/chunk_index": chunk,
                    f"videos/{key}/file_index": file,
                    f"videos/{key}/from_timestamp": 0.0,
                    f"videos/{key}/to_timestamp": length / self.fps,
                }
            )
        row["stats"] = self._stats(length)
        return row

    def commit(self) -> None:
        """The episode's files under their own names: readers see the episode from now."""
        for tmp, final in self._temporary:
            move_into_place(tmp, final)

    def abort(self) -> None:
        """Drop what was written of an episode that will not finish."""
        for container, _ in self._videos.values():
            try:
                container.close()
            except Exception:  # a half-open container: its file goes anyway
                pass
        for tmp, _ in self._temporary:
            tmp.unlink(missing_ok=True)

    def _table(self, length: int) -> pa.Table:
        columns: dict[str, pa.Array] = {}
        for key, feature in self.features.items():
            if feature.dtype == "video":
                continue
            array = np.asarray(self.values[key], dtype=_numpy(feature.dtype)).reshape(length, -1)
            columns[key] = _column(array, feature)
        frame = np.arange(length)
        columns["timestamp"] = pa.array((frame / self.fps).astype(np.float32))
        columns["frame_index"] = pa.array(frame, type=pa.int64())
        columns["episode_index"] = pa.array(np.full(length, self.episode), type=pa.int64())
        columns["index"] = pa.array(frame, type=pa.int64())
        columns["task_index"] = pa.array(np.full(length, self.task_index), type=pa.int64())
        return pa.table(columns)

    def _stats(self, length: int) -> dict[str, dict[str, Any]]:
        stats = {}
        for key, feature in self.features.items():
            if feature.dtype == "video":
                pixels = np.stack(self._pixels[key]).astype(np.float64) / 255.0
                per_channel = pixels.reshape(-1, pixels.shape[-1])
                stats[key] = {k: v.reshape(-1, 1, 1) for k, v in _summary(per_channel).items()}
                stats[key]["count"] = np.array([length])
            else:
                values = np.asarray(self.values[key], dtype=np.float64).reshape(length, -1)
                stats[key] = _summary(values) | {"count": np.array([length])}
        frame = np.arange(length, dtype=np.float64)[:, None]
        for key, values in (
            ("timestamp", frame / self.fps),
            ("frame_index", frame),
            ("episode_index", np.full_like(frame, self.episode)),
            ("index", frame),
            ("task_index", np.full_like(frame, self.task_index)),
        ):
            stats[key] = _summary(values) | {"count": np.array([length])}
        return stats


def _numpy(dtype: str) -> Any:
    return {"float32": np.float32, "int64": np.int64, "bool": np.bool_}[dtype]


def _column(array: np.ndarray, feature: Feature) -> pa.Array:
    """A scalar column for shape (1,), else a fixed-size list, as lerobot's reader casts."""
    kind = {"float32": pa.float32(), "int64": pa.int64(), "bool": pa.bool_()}[feature.dtype]
    if tuple(feature.shape) == (1,):
        return pa.array(array[:, 0], type=kind)
    flat = pa.array(array.reshape(-1), type=kind)
    return pa.FixedSizeListArray.from_arrays(flat, int(np.prod(feature.shape)))


def _summary(values: np.ndarray) -> dict[str, np.ndarray]:
    summary = {
        "min": values.min(axis=0),
        "max": values.max(axis=0),
        "mean": values.mean(axis=0),
        "std": values.std(axis=0),
    }
    for q in QUANTILES:
        summary[f"q{int(q * 100):02d}"] = np.quantile(values, q, axis=0)
    return summary
