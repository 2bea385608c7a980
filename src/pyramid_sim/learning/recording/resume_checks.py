"""What a folder must hold before a recording writes into it: nothing yet, or a dataset
pyramid-sim recorded there, every episode it claims whole.

A folder of someone else's (lerobot's own dataset, one whose `meta/pyramid_sim/` is gone, a
build's result) would have its `meta/info.json` and episode files overwritten, and an episode
file cut short would be counted as recorded: both are refused before anything is written,
naming what is there. A damaged episode is recorded again only when asked (`repair`).
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from ...errors import ConfigError
from ...output.files import check_writable_dir
from ...output.lock import LOCK_NAME
from ..dataset import lerobot_format as fmt
from .staging import STAGING

RECORDS = "meta/pyramid_sim"  # pyramid_sim's own files, where lerobot does not look
IMAGES = "observation.images."
# What a first run killed before its first episode's record landed can leave (the record is
# the first of the metadata written): that episode's own files, temporary files, the staging
# area and the lock. A folder holding only these is the start of a recording.
LEFT_BY_A_FIRST_RUN = (
    r"data/chunk-\d{3}/(file-\d{3}\.parquet|\.file-\d{3}\..*\.part)",
    r"videos/[^/]+/chunk-\d{3}/(file-\d{3}\.mp4|\.file-\d{3}\..*\.part)",
    re.escape(STAGING) + r"/.*",
    r"replay/(episode_\d{6}|meshes_[0-9a-f]+)\.npz",  # the episodes' poses, for a replay
    re.escape(LOCK_NAME),
)
SHOWN = 3  # foreign files named in a refusal
DATASET_TOPS = ("data", "videos", "meta", STAGING)  # the folders a recording writes in


def read_records(out: Path) -> tuple[dict[int, dict[str, Any]], dict[int, str]]:
    """The episode records in `out` by episode, and the episodes whose record cannot be read
    (cut short, or without what a record holds), with what is wrong."""
    records: dict[int, dict[str, Any]] = {}
    unreadable: dict[int, str] = {}
    for path in sorted((out / RECORDS).glob("episode_*.json")):
        name = str(path.relative_to(out))
        try:
            record = json.loads(path.read_text())
            index = int(record["episode_index"])
            int(record["row"]["length"])
        except (OSError, ValueError, KeyError, TypeError) as err:
            found = re.fullmatch(r"episode_(\d+)\.json", path.name)
            if found is None:
                continue  # not one of ours: left alone
            unreadable[int(found[1])] = f"{name} cannot be read ({type(err).__name__}: {err})"
            continue
        records[index] = record
    return records, unreadable


def check_folder(out: Path, recorded: bool) -> None:
    """ConfigError if `out` holds files a recording did not write there: only a dataset of
    pyramid-sim's (`recorded`: it has episode records) may be resumed, and only a folder that
    is new, empty or the leftovers of a first run killed early may be started in."""
    if recorded or not out.is_dir() or (out / RECORDS / "dataset.json").exists():
        return
    foreign = [name for name in _files(out) if not _left_by_a_first_run(name)]
    if foreign:
        shown = ", ".join(foreign[:SHOWN]) + (
            f" and {len(foreign) - SHOWN} more" if len(foreign) > SHOWN else ""
        )
        kind = (
            "a LeRobot dataset pyramid-sim did not record"
            if "meta/info.json" in foreign
            else "files"
        )
        raise ConfigError(
            f"out: {str(out)!r} holds {kind} ({shown}), which this recording would "
            "overwrite or mix with its own; accepted a new or empty folder, or a dataset "
            f"pyramid-sim recorded (with its {RECORDS}/)"
        )


def damaged_episodes(out: Path, records: dict[int, dict[str, Any]]) -> dict[int, str]:
    """Each recorded episode whose files are not whole, with what is wrong: its data file and
    each camera's video must open and hold the frames its record claims."""
    damaged = {}
    for index, record in sorted(records.items()):
        problem = episode_problem(out, index, record)
        if problem:
            damaged[index] = problem
    return damaged


def episode_problem(out: Path, index: int, record: dict[str, Any]) -> str:
    """What is wrong with episode `index`'s files, or ""."""
    chunk, file = fmt.location(index)
    length = int(record["row"]["length"])
    data = fmt.DATA_PATH.format(chunk_index=chunk, file_index=file)
    problem = _frames_problem(out, data, length, _parquet_rows)
    for key in (f for f in record.get("features", ()) if f.startswith(IMAGES)):
        if problem:
            break
        video = fmt.VIDEO_PATH.format(video_key=key, chunk_index=chunk, file_index=file)
        problem = _frames_problem(out, video, length, _video_frames)
    return problem


def refusal(out: Path, damaged: dict[int, str]) -> ConfigError:
    """The one line that refuses to resume over damaged episodes, naming them."""
    first = min(damaged)
    more = f" (and episodes {_listed(sorted(damaged)[1:])})" if len(damaged) > 1 else ""
    return ConfigError(
        f"out: {str(out)!r} has a damaged episode {first}{more}: {damaged[first]}; accepted "
        "--repair (repair=True) to record it again, or a new folder"
    )


def forget(out: Path, episodes: Iterable[int]) -> None:
    """Take episodes out of the dataset by removing their records: their files then go as an
    unrecorded episode's do, and they are recorded again as missing ones."""
    for index in episodes:
        (out / RECORDS / f"episode_{index:06d}.json").unlink(missing_ok=True)


def check_resumable(
    out: Path,
    records: dict[int, dict[str, Any]],
    damaged: dict[int, str],
    episodes: int,
    policy: str | None,
    repair: bool,
) -> None:
    """ConfigError, before any work, for what a resumed run would lose or get wrong: a folder
    it cannot write in, a damaged episode past `episodes` (its repair would delete it), one
    a repair would record with another driver than its own (the expert for a DAgger
    episode), and a dataset whose description is missing or broken, unless `repair`."""
    for folder in [out, *(p for t in DATASET_TOPS for p in _folders(out / t))]:
        check_writable_dir(folder)
    beyond = sorted(i for i in damaged if i >= episodes)
    if repair and beyond:
        raise ConfigError(
            f"out: {str(out)!r} has a damaged episode {beyond[0]}, past the {episodes} "
            f"episodes asked for, so repairing would delete it; accepted --episodes "
            f"{beyond[-1] + 1} or more to record it again"
        )
    for index in sorted(damaged) if repair else ():
        driver = records.get(index, {}).get("driver", {}).get("policy")
        if index in records and driver != policy:
            was = "the expert" if driver is None else f"the policy {driver!r} (DAgger)"
            now = "the expert" if policy is None else f"the policy {policy!r}"
            raise ConfigError(
                f"out: {str(out)!r} has a damaged episode {index} driven by {was}, which "
                f"--repair would record again driven by {now}; accepted "
                + ("no --policy" if driver is None else f"--policy {driver}")
                + " with --repair"
            )
    problem = description_problem(out) if records and not repair else ""
    if problem:
        raise ConfigError(
            f"out: {str(out)!r} has {problem}; accepted --repair (repair=True) to write it "
            "again from this run's settings, or a new folder"
        )


def description_problem(out: Path) -> str:
    """What is wrong with the dataset's own description (meta/pyramid_sim/dataset.json),
    or "" when it is a JSON object naming the structure."""
    name = f"{RECORDS}/dataset.json"
    try:
        document = json.loads((out / name).read_bytes())
    except FileNotFoundError:
        return f"no {name}"
    except (OSError, ValueError) as err:
        return f"a {name} that cannot be read ({type(err).__name__}: {err})"
    if not isinstance(document, dict) or "structure" not in document:
        return f"a {name} that is not a dataset's description"
    return ""


def _folders(top: Path) -> list[Path]:
    if not top.is_dir() or top.is_symlink():
        return []
    return [top, *(p for p in top.rglob("*") if p.is_dir() and not p.is_symlink())]


def _frames_problem(out: Path, name: str, length: int, count: Any) -> str:
    path = out / name
    if not path.is_file():
        return f"{name} is missing"
    try:
        frames = count(path)
    except Exception as err:  # a reader's own errors, whatever the library: unreadable
        return f"{name} cannot be read ({type(err).__name__}: {err})"
    if frames != length:
        return f"{name} holds {frames} frames where its record claims {length}"
    return ""


def _parquet_rows(path: Path) -> int:
    import pyarrow.parquet as pq

    return int(pq.ParquetFile(path).metadata.num_rows)


def _video_frames(path: Path) -> int:
    import av

    with av.open(str(path)) as container:
        return int(container.streams.video[0].frames)


def _files(out: Path) -> list[str]:
    """The files of `out`, looked into only where a dataset keeps them: any other name at the
    top is named as it is (a folder such as / is not walked)."""
    found = []
    for top in sorted(out.iterdir()):
        if top.name in DATASET_TOPS and top.is_dir() and not top.is_symlink():
            found += sorted(str(p.relative_to(out)) for p in top.rglob("*") if not p.is_dir())
        else:
            found.append(top.name)
    return found


def _left_by_a_first_run(name: str) -> bool:
    return any(re.fullmatch(pattern, name) for pattern in LEFT_BY_A_FIRST_RUN)


def _listed(numbers: list[int]) -> str:
    return ", ".join(map(str, numbers[:SHOWN])) + (" ..." if len(numbers) > SHOWN else "")
