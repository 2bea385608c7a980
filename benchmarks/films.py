"""Films beside a leaderboard row: of its own evaluation, one success and one failure chosen by
the scores (never by hand), each a short MP4 under 1 MB and a 3D replay page.

The choice: the success whose length is the median of the successes' (a typical success), and
of the commonest kind of failure, the episode whose bricks placed are the median of that
kind's (a typical failure); ties go to the lower seed. Each chosen episode is run again from
its seed (an episode depends on its seed alone, docs/evaluation.md), filmed and taped, and
its row must come out the same as the evaluation's: a film is of the row's own episode, or is
not made.

    row_films(checkpoint, recipe, evaluation_dir, dest, row_document)

writes dest/NAME-success.mp4, .html, NAME-failure.mp4, .html (where there are such episodes)
and dest/NAME.json, the manifest the leaderboard links from.
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
from collections import Counter
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))  # rows.py beside it

from rows import Recipe  # noqa: E402

from pyramid_sim.learning.evaluation.scores import failure_kind  # noqa: E402
from pyramid_sim.output.replay_page import write_page  # noqa: E402

FILM_LIMIT = 1_000_000  # bytes: small enough to commit
SPEEDUP = 4  # an episode of a minute is a film of 15 s
# (width, x264's constant rate factor): tried in turn until the film fits FILM_LIMIT
ENCODINGS = ((480, 30), (400, 34), (320, 38), (240, 42))
SAME = ("success", "bricks_placed", "failure", "steps")  # what a rerun must repeat


def pick(rows: list[dict[str, Any]]) -> dict[str, dict[str, Any]]:
    """The success and the failure the row's films show (either missing where the evaluation
    has none), chosen by the rows' scores alone."""
    chosen = {}
    wins = sorted((r for r in rows if r["success"]), key=lambda r: (r["steps"], r["seed"]))
    if wins:
        chosen["success"] = _median(wins, "steps")
    losses = [r for r in rows if not r["success"]]
    if losses:
        kinds = Counter(failure_kind(r["failure"]) or "other" for r in losses)
        common = min(kinds, key=lambda k: (-kinds[k], k))
        of_kind = [r for r in losses if (failure_kind(r["failure"]) or "other") == common]
        chosen["failure"] = _median(
            sorted(of_kind, key=lambda r: (r["bricks_placed"], r["seed"])), "bricks_placed"
        )
    return chosen


def _median(ordered: list[dict[str, Any]], key: str) -> dict[str, Any]:
    """The lower median of rows ordered by `key` (then seed): the lowest seed of its value."""
    value = ordered[(len(ordered) - 1) // 2][key]
    return next(r for r in ordered if r[key] == value)


def shrink(film: Path, out: Path) -> None:
    """`film` sped up SPEEDUP times, smaller, as an H.264 MP4 under FILM_LIMIT (the first of
    ENCODINGS that fits); RuntimeError if none does."""
    import imageio_ffmpeg

    for width, crf in ENCODINGS:
        command = [
            imageio_ffmpeg.get_ffmpeg_exe(),
            "-y",
            "-loglevel",
            "error",
            "-i",
            str(film),
            "-vf",
            f"setpts=PTS/{SPEEDUP},scale={width}:-2",
            "-an",
            "-c:v",
            "libx264",
            "-preset",
            "slow",
            "-crf",
            str(crf),
            "-pix_fmt",
            "yuv420p",
            "-movflags",
            "+faststart",
            str(out),
        ]
        subprocess.run(command, check=True)
        if out.stat().st_size < FILM_LIMIT:
            return
    out.unlink()
    raise RuntimeError(f"{film}: no encoding of it fits {FILM_LIMIT} bytes")


def rerun(
    checkpoint: str, recipe: Recipe, seed: int, out: Path, episodes: int = 1
) -> dict[str, Any]:
    """The evaluation's episodes from `seed` again, filmed and taped into `out`: its scores.
    The same call as baseline.py's `score`, on `episodes` (the first filmed)."""
    import pyramid_sim

    evaluation = pyramid_sim.evaluate(
        checkpoint,
        recipe.structure,
        out=out,
        robot=recipe.robot,
        layers=recipe.eval_layers or recipe.layers,
        variation=recipe.variation,
        episodes=episodes,
        seed=seed,
        video=1,
        max_steps=recipe.max_steps,
        action_mode=recipe.action_mode,
        fps=recipe.fps,
    )
    return evaluation.scores


def row_films(
    checkpoint: str | Path,
    recipe: Recipe,
    evaluation_dir: Path,
    dest: Path,
    row_document: dict[str, Any],
) -> Path:
    """The row's films and replay pages in `dest`, and its manifest dest/ROW.json (returned):
    for each film, the episode's row, and the files."""
    rows = json.loads((evaluation_dir / "evaluation.json").read_text())["rows"]
    dest.mkdir(parents=True, exist_ok=True)
    films: dict[str, Any] = {}
    for kind, row in pick(rows).items():
        with tempfile.TemporaryDirectory(prefix="pyramid-sim-films-") as tmp:
            again = rerun(str(checkpoint), recipe, row["seed"], Path(tmp) / "run")["rows"][0]
            if any(again[k] != row[k] for k in SAME):
                print(
                    f"films: {recipe.row} seed {row['seed']} ran otherwise again "
                    f"({ {k: again[k] for k in SAME} }): no {kind} film",
                    file=sys.stderr,
                )
                continue
            name = f"{recipe.row}-{kind}"
            shrink(Path(tmp) / "run" / f"episode_{row['seed']}.mp4", dest / f"{name}.mp4")
            write_page(
                Path(tmp) / "run" / "replay" / "episode_000000.npz",
                dest / f"{name}.html",
                overwrite=True,
            )
        films[kind] = {
            "episode": {k: row[k] for k in ("seed", *SAME)},
            "film": f"{name}.mp4",
            "page": f"{name}.html",
        }
    manifest = dest / f"{recipe.row}.json"
    document = {"row": recipe.row, "finished": row_document["finished"], "films": films}
    manifest.write_text(json.dumps(document, indent=1) + "\n")
    return manifest


def films_beside(
    checkpoint: Path, recipe: Recipe, evaluation_dir: Path, dest: Path, row: str
) -> None:
    """`row_films` for baseline.py, after its row is written (`row`, its result file's
    text): a film that cannot be made is said in one line, and the row stands without it."""
    from pyramid_sim.errors import PyramidSimError

    try:
        manifest = row_films(checkpoint, recipe, evaluation_dir, dest, json.loads(row))
    except (PyramidSimError, OSError, RuntimeError, subprocess.CalledProcessError) as error:
        print(f"films: {recipe.row}: none made ({error})", file=sys.stderr)
        return
    print(f"films: {recipe.row} -> {manifest}")
