"""A row's learning curve, with `--curve N`: every saved checkpoint of the last training
scored on N seeds, into DIR/curve.json and DIR/curve.png."""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))  # rows.py beside it

from row_paths import training, write_whole  # noqa: E402
from row_scoring import score  # noqa: E402
from rows import Recipe  # noqa: E402


def curve(out: Path, recipe: Recipe) -> None:
    """Every saved checkpoint of the last training scored on `curve_episodes` seeds:
    curve.json and curve.png."""
    points = []
    last = training(out, len(recipe.rounds))
    for folder in sorted((last / "checkpoints").glob("[0-9]*")):
        scores = score(folder / "pretrained_model", recipe, recipe.curve_episodes, None)
        point = {"step": int(folder.name), "success_rate": scores["success_rate"]}
        points.append({**point, "interval": scores["success_rate_95"]})
    write_whole(out / "curve.json", json.dumps(points, indent=1) + "\n")
    plot(points, recipe, out / "curve.png")


def plot(points: list[dict[str, Any]], recipe: Recipe, path: Path) -> None:
    """Success against training steps, with its 95 % interval."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(figsize=(5, 3.2))
    steps = [p["step"] for p in points]
    axes.plot(steps, [100 * p["success_rate"] for p in points], "o-")
    low = [100 * p["interval"][0] for p in points]
    high = [100 * p["interval"][1] for p in points]
    axes.fill_between(steps, low, high, alpha=0.2)
    title = f"{recipe.structure} {recipe.layers}, {recipe.robot}: "
    title += f"{recipe.curve_episodes} seeds a point"
    axes.set(xlabel="training steps", ylabel="success (%)", ylim=(0, 100), title=title)
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    plt.close(figure)
