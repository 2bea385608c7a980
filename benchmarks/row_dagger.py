"""DAgger's rounds of a row: each records its episodes with the last policy driving the spans
its expert does not, the expert labelling every frame, and trains on from that policy; and
what each round added to the recording."""

from __future__ import annotations

import json
import sys
from dataclasses import asdict
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))  # rows.py beside it

from row_paths import checkpoint  # noqa: E402
from row_recording import built, record  # noqa: E402
from row_training import train, trained_before  # noqa: E402
from rows import Recipe, Round  # noqa: E402


def dagger(out: Path, recipe: Recipe, seconds: dict[str, float]) -> list[dict[str, Any]]:
    """DAgger's rounds: each records its episodes with the last policy driving and trains
    on from it (a round's training found finished is kept); what each added (episodes, kept,
    learner's share). Each stage's seconds go into `seconds`."""
    added = []
    total = recipe.demos
    for k, round_ in enumerate(recipe.rounds, start=1):
        before = total
        total += round_.episodes
        driver = {"policy": str(checkpoint(out, k - 1)), "beta": round_.beta}
        if round_.takeover is not None:
            driver["takeover"] = round_.takeover
        seconds[f"record_r{k}"] = record(out, recipe, total, f"recording round {k}", **driver)
        done = trained_before(out, k, round_.steps)
        seconds[f"train_r{k}"] = done if done is not None else train(out, recipe, k, round_.steps)
        added.append(round_summary(out / "demos", range(before, total), round_))
    return added


def round_summary(demos: Path, episodes: range, round_: Round) -> dict[str, Any]:
    """What a round's `episodes` added: how many built, how many are learned from, and the
    learner's share of their frames."""
    records = [
        json.loads((demos / "meta" / "pyramid_sim" / f"episode_{i:06d}.json").read_text())
        for i in episodes
    ]
    frames = sum(r["row"]["length"] for r in records)
    learner = sum(r["driver"]["learner_steps"] for r in records)
    takeovers = sum(r["driver"].get("takeovers", 0) for r in records)
    kept = set(built(demos))
    return {
        **asdict(round_),
        "built": sum(r["success"] for r in records),
        "kept": sum(i in kept for i in episodes),
        "learner_share": learner / frames if frames else 0.0,
        "takeovers": takeovers,
    }
