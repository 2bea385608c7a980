"""A row's scoring: a checkpoint scored by `pyramid-sim evaluate` on held-out seeds, each
DAgger round's policy on the same seeds (what the round gained), and the `lerobot-eval` line
that scores the row's checkpoint through the plugin."""

from __future__ import annotations

import json
import shlex
import sys
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))  # rows.py beside it

from row_paths import checkpoint  # noqa: E402
from row_training import env_flags  # noqa: E402
from rows import Recipe  # noqa: E402
from stage_progress import stage  # noqa: E402

from pyramid_sim.choices import EVAL_FIRST_SEED  # noqa: E402

# what a round's score keeps of its evaluation
ROUND_SCORES = ("episodes", "successes", "success_rate", "success_rate_95", "bricks_placed_mean")


def score(
    checkpoint: Path,
    recipe: Recipe,
    episodes: int,
    out: Path | None,
    layers: int | None = None,
) -> dict[str, Any]:
    """`checkpoint` scored on `episodes` held-out seeds, at the recipe's size or `layers`;
    with `out`, its evaluation.json written there (the bar named for it)."""
    import pyramid_sim

    desc = "scoring" if out is None else f"scoring {out.name}"
    with stage(desc, episodes, "episode") as progress:
        progress.start()
        evaluation = pyramid_sim.evaluate(
            str(checkpoint),
            recipe.structure,
            out=out,
            robot=recipe.robot,
            layers=layers or recipe.layers,
            variation=recipe.variation,
            episodes=episodes,
            max_steps=recipe.max_steps,
            action_mode=recipe.action_mode,
            fps=recipe.fps,
            workers=recipe.workers,
            on_episode=lambda row: progress.advance(),
        )
    return evaluation.scores


def round_scores(out: Path, recipe: Recipe) -> list[dict[str, Any]]:
    """Each round's policy (round 0 the first training's) scored on `round_episodes` seeds
    from the evaluation's first, into DIR/round_K: what each DAgger round gained. A round
    scored before is read back."""
    scored = []
    for k in range(len(recipe.rounds) + 1):
        folder = out / f"round_{k}"
        done = folder / "evaluation.json"
        if done.is_file():
            scores = json.loads(done.read_text())
        else:
            scores = score(checkpoint(out, k), recipe, recipe.round_episodes, folder)
        scored.append({"round": k, **{name: scores[name] for name in ROUND_SCORES}})
    return scored


def lerobot_eval_line(checkpoint: Path, out: Path, recipe: Recipe) -> str:
    """The lerobot-eval command that scores `checkpoint` on the evaluation's seeds:
    lerobot-eval takes no env from a checkpoint (its --config_path refuses a train_config),
    so the env's flags are repeated."""
    return shlex.join(
        [
            "lerobot-eval",
            f"--policy.path={checkpoint}",
            "--policy.device=cpu",
            *env_flags(recipe),
            f"--eval.n_episodes={recipe.episodes}",
            "--eval.batch_size=1",
            f"--seed={EVAL_FIRST_SEED}",
            f"--output_dir={out / 'lerobot_eval'}",
        ]
    )
