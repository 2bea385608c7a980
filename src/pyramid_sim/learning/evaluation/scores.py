"""How an evaluation is scored, MuJoCo-free: a success rate with its 95 % Wilson interval,
bricks placed, failures grouped by kind, episode lengths."""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Sequence
from typing import Any

Z95 = 1.959963984540054  # the normal quantile of a two-sided 95 % interval
# A failure's kind: the first of these phrases its text holds (texts carry numbers).
KINDS = (
    ("torque limit", "torque limit"),
    ("velocity limit", "speed limit"),
    ("arm-arm contact", "arm-arm contact"),
    ("left the table", "brick off the table"),
    ("did not finish within", "time limit"),
    ("step limit", "step limit"),
    ("no motion", "no motion within the limits"),
    ("dropped", "bricks dropped"),
    ("warning", "physics warning"),
)


def wilson_interval(successes: int, n: int) -> tuple[float, float]:
    """The 95 % Wilson score interval of a success rate (0 to 1); (0, 1) with no trial."""
    if n == 0:
        return 0.0, 1.0
    p = successes / n
    z2 = Z95 * Z95
    centre = (p + z2 / (2 * n)) / (1 + z2 / n)
    half = Z95 * math.sqrt(p * (1 - p) / n + z2 / (4 * n * n)) / (1 + z2 / n)
    return max(0.0, centre - half), min(1.0, centre + half)


def failure_kind(failure: str | None) -> str | None:
    """The kind of an episode's failure text (None for none; "other" for a text no kind
    names)."""
    if failure is None:
        return None
    for phrase, kind in KINDS:
        if phrase in failure:
            return kind
    return "other"


def summary(rows: Sequence[dict[str, Any]], bricks: int) -> dict[str, Any]:
    """The scores of episode rows (each with success, bricks_placed, failure, steps): the
    success rate and its interval, bricks placed (mean and how many episodes placed each
    count), failures by kind, episode lengths in steps."""
    n = len(rows)
    wins = sum(bool(r["success"]) for r in rows)
    low, high = wilson_interval(wins, n)
    placed = Counter(int(r["bricks_placed"]) for r in rows)
    kinds = Counter(k for k in (failure_kind(r["failure"]) for r in rows) if k is not None)
    steps = [int(r["steps"]) for r in rows]
    return {
        "episodes": n,
        "successes": wins,
        "success_rate": wins / n if n else 0.0,
        "success_rate_95": [low, high],
        "bricks": bricks,
        "bricks_placed_mean": sum(r["bricks_placed"] for r in rows) / n if n else 0.0,
        "bricks_placed_episodes": {str(k): placed.get(k, 0) for k in range(bricks + 1)},
        "failures": dict(sorted(kinds.items())),
        "episode_steps": {
            "mean": sum(steps) / n if n else 0.0,
            "min": min(steps, default=0),
            "max": max(steps, default=0),
        },
    }
