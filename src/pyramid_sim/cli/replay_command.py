"""`pyramid-sim replay RUN --html FILE`: a run's 3D replay as one HTML page that opens from
disk (no server, no network): the table, the bricks and both arms, a time slider, play and
pause, and a camera to turn round with the mouse.

RUN is a build's folder (its replay.npz), an evaluation's or a recording's folder with
`--episode N` (its replay/episode_N.npz, N from 0), or such a .npz file itself.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from ..errors import ConfigError
from ..output.files import check_writable_dir
from ..output.replay_tape import EPISODES_FOLDER, REPLAY_FILE, episode_file
from .args import output_path, whole

RUNS = (
    "a build's folder (with replay.npz), an evaluation's or a recording's folder (with "
    "replay/), or a replay .npz file"
)
ACCEPTED = f"accepted {RUNS}"


def add_replay_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("run", type=Path, metavar="RUN", help=f"the run: {RUNS}")
    p.add_argument(
        "--html",
        type=output_path("html", folder=False),
        required=True,
        metavar="FILE.html",
        help="the page to write (one self-contained file)",
    )
    p.add_argument(
        "--episode",
        type=whole("episode", "0 or more"),
        metavar="N",
        help="of an evaluation or a recording: the episode's index, from 0 (default: the "
        "only one, where there is one)",
    )
    p.add_argument(
        "--overwrite", action="store_true", help="replace FILE.html if it exists (default: refuse)"
    )


def tape_of(run: Path, episode: int | None) -> Path:
    """The replay file of `run` (and `episode`); ConfigError naming what is wrong: a RUN
    missing, not a run, or a run without poses, or an episode it does not hold."""
    if not run.exists():
        raise ConfigError(f"run: {str(run)!r} does not exist; {ACCEPTED}")
    if run.is_file():
        if run.suffix != ".npz":
            raise ConfigError(f"run: {str(run)!r} is not a run; {ACCEPTED}")
        return run
    if (run / "result.json").is_file():
        if episode is not None:
            raise ConfigError(
                f"episode: {str(run)!r} is a build, one episode; accepted no --episode"
            )
        if not (run / REPLAY_FILE).is_file():
            raise ConfigError(
                f"run: {str(run)!r} is a build without poses (no {REPLAY_FILE}: built before "
                "pyramid-sim kept them); build it again to replay it"
            )
        return run / REPLAY_FILE
    if not ((run / "evaluation.json").is_file() or (run / "meta" / "info.json").is_file()):
        raise ConfigError(
            f"run: {str(run)!r} is not a run (no result.json, evaluation.json "
            f"or meta/info.json); {ACCEPTED}"
        )
    taped = sorted((run / EPISODES_FOLDER).glob("episode_*.npz"))
    if not taped:
        raise ConfigError(
            f"run: {str(run)!r} holds no episode's poses (no {EPISODES_FOLDER}/: written "
            "before pyramid-sim kept them); run it again to replay it"
        )
    if episode is None and len(taped) > 1:
        raise ConfigError(
            f"episode: {str(run)!r} holds {len(taped)} episodes; accepted "
            f"--episode 0 to {len(taped) - 1}"
        )
    path = episode_file(run, 0 if episode is None else episode)
    if not path.is_file():
        raise ConfigError(
            f"episode: {str(run)!r} holds no episode {episode}; accepted "
            f"--episode 0 to {len(taped) - 1}"
        )
    return path


def cmd_replay(args: argparse.Namespace) -> int:
    """Write the page; print its frames, length and size."""
    from ..output.replay_page import write_page

    tape_path = tape_of(args.run, args.episode)
    check_writable_dir(args.html.parent, "html")
    tape, size = write_page(tape_path, args.html, args.overwrite)
    frames = len(tape["time"])
    print(
        f"replay: {json.dumps(str(tape['title']))[1:-1]}, {frames} frames over "
        f"{float(tape['time'][-1] - tape['time'][0]):.1f} s, {size / 1e6:.2f} MB "
        f"-> {args.html}"
    )
    return 0
