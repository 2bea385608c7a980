"""A row's recording: the expert's demonstrations with DART's noise, and each DAgger round's
episodes, into DIR/demos (episodes there kept, those missing recorded); and which of them a
policy learns from."""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))  # rows.py beside it

from rows import Recipe  # noqa: E402
from stage_progress import stage  # noqa: E402


def record(
    out: Path, recipe: Recipe, episodes: int | None = None, desc: str = "recording", **driver: Any
) -> float:
    """The dataset's first `episodes` (the demonstrations by default), those missing recorded:
    by the expert, or with `driver` (policy, beta) a DAgger round's. Its seconds."""
    import pyramid_sim

    wanted = episodes or recipe.demos
    noise = 0.0 if driver else recipe.noise  # a learner's episodes: the expert labels, clean
    start = time.perf_counter()
    with stage(desc, wanted, "episode", count_unit="frame") as progress:
        on_frame, on_episode = progress.recording_hooks()
        pyramid_sim.record(
            recipe.task,  # the spec whole: every field as the recipe has it
            out=out / "demos",
            episodes=wanted,
            seed=0,
            noise=noise,
            workers=recipe.workers,
            on_frame=on_frame,
            on_episode=on_episode,
            **driver,
        )
    return time.perf_counter() - start


def built(demos: Path) -> list[int]:
    """The recorded episodes to learn from: the expert's demonstrations that built (one that
    failed ends holding still by a misplaced brick for the rest of its step limit, which no
    policy should learn), and DAgger's episodes but those that ran to the step limit (the
    expert's labels are right in every state a learner reached, up to a failure; at the
    step limit the expert held still by a brick it cannot set right)."""
    return [
        e["episode_index"]
        for e in episode_records(demos)
        if e["success"] or (e.get("driver") and "step limit" not in (e.get("failure") or ""))
    ]


def episode_records(demos: Path) -> list[dict[str, Any]]:
    """The recording's own record of each episode (meta/pyramid_sim/episode_N.json), in order."""
    records = sorted((demos / "meta" / "pyramid_sim").glob("episode_*.json"))
    return [json.loads(p.read_text()) for p in records]
