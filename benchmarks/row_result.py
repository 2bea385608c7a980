"""A row's result file: what the leaderboard shows (the score, the task, the policy and its
inputs) and everything that made it (the recipe, the demonstrations, DAgger's rounds, the
seconds each stage took, the machine, the versions and the commit)."""

from __future__ import annotations

import os
import platform
import subprocess
import sys
from dataclasses import asdict
from datetime import datetime, timezone
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))  # rows.py beside it

from families import LABELS  # noqa: E402
from row_recording import episode_records  # noqa: E402
from row_scoring import lerobot_eval_line  # noqa: E402
from rows import Recipe  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
# what the result file keeps of the evaluation's scores
SCORE = (
    "episodes",
    "successes",
    "success_rate",
    "success_rate_95",
    "bricks_placed_mean",
    "failures",
    "protocol",
)


def result(
    recipe: Recipe,
    evaluation: dict[str, Any],
    seconds: dict[str, float],
    demos: Path,
    rounds: list[dict[str, Any]],
    gain: list[dict[str, Any]] | None = None,
) -> dict[str, Any]:
    """The row's result file: what the leaderboard shows and everything that made it."""
    expert = [r for r in episode_records(demos) if not r.get("driver")]
    return {
        "row": recipe.row,
        "track": recipe.track,
        "task": task(recipe, evaluation["bricks"]),
        "robot": recipe.robot,
        "policy": LABELS[recipe.policy],
        "action_mode": recipe.action_mode,
        "inputs": ["state", environment_inputs(recipe), *recipe.cameras],
        "demos": {
            "recorded": len(expert),
            "built": sum(r["success"] for r in expert),
            "noise": recipe.noise,
        },
        "dagger": {"rounds": rounds, "scores": gain or []},
        "score": {k: evaluation[k] for k in SCORE},
        "training_steps": recipe.steps + sum(r.steps for r in recipe.rounds),
        "seconds": seconds,
        "machine": machine(),
        "commit": commit(),
        "versions": {**evaluation["versions"], **learner_versions()},
        "recipe": asdict(recipe),
        "command": f"python benchmarks/baseline.py --row {recipe.row} --out DIR",
        "lerobot_eval": lerobot_eval_line(Path("DIR/CHECKPOINT"), Path("DIR"), recipe),
        "finished": datetime.now(timezone.utc).isoformat(timespec="seconds"),
    }


def task(recipe: Recipe, bricks: int) -> dict[str, Any]:
    """The task the row is scored on: at its evaluation's size, its training's beside it."""
    return {
        "structure": recipe.structure,
        "layers": recipe.eval_layers or recipe.layers,
        "bricks": bricks,
        "variation": recipe.variation,
        "trained_layers": recipe.layers,
    }


def environment_inputs(recipe: Recipe) -> str:
    """What of the environment state the row's policy sees, in words."""
    left_out = [] if recipe.brick_poses else ["the bricks' poses"]
    left_out += [] if recipe.all_goals else ["the goals but each arm's next"]
    return "environment_state" + (f" without {' and '.join(left_out)}" if left_out else "")


def machine() -> dict[str, Any]:
    """Where the row ran: the CPU, its cores, and the accelerator if torch sees one."""
    cpu = platform.processor() or platform.machine()
    found: dict[str, Any] = {"cpu": cpu, "cores": os.cpu_count(), "gpu": None}
    try:
        import torch

        if torch.cuda.is_available():
            found["gpu"] = torch.cuda.get_device_name(0)
    except ImportError:
        pass
    return found


def learner_versions() -> dict[str, str]:
    """The versions of what trained the policy: lerobot and torch, where they import."""
    found = {}
    for name in ("lerobot", "torch"):
        try:
            found[name] = str(__import__(name).__version__)
        except ImportError:
            found[name] = "not installed"
    return found


def commit() -> str:
    """The commit the row ran at, `+dirty` if the checkout had changes."""

    def git(*args: str) -> str:
        done = subprocess.run(["git", *args], cwd=REPO, capture_output=True, text=True)
        return done.stdout.strip()

    head = git("rev-parse", "HEAD") or "unknown"
    return head + ("+dirty" if git("status", "--porcelain", "--", "src", "benchmarks") else "")
