"""The plot `evaluate` writes beside evaluation.json, drawn from the file alone: a bar an
episode coloured by the bricks it placed, and the failures' kinds against the brick they
happened on."""

import json

import numpy as np
from PIL import Image

from pyramid_sim.learning.evaluation.plot import plot_evaluation_file
from pyramid_sim.learning.evaluation.scores import summary


def evaluation(rows):
    scores = {"policy": "act", **summary(rows, 6), "rows": rows}
    scores["task"] = {"structure": "pyramid", "size": {"layers": 3}, "robot": "panda"}
    return scores


def row(seed, placed, failure=None):
    return {
        "seed": seed,
        "success": failure is None,
        "bricks_placed": placed,
        "failure": failure,
        "steps": 100,
    }


ROWS = [row(100000 + i, 6) for i in range(7)] + [
    row(100007, 2, "left arm: torque limit on joint 4"),
    row(100008, 2, "left arm: torque limit on joint 4"),
    row(100009, 4, "step limit: 4000 steps"),
]


def _colours(png):
    pixels = np.asarray(Image.open(png).convert("RGB")).astype(int).reshape(-1, 3)
    r, g, b = pixels.T
    green = ((g > 90) & (g > r + 40) & (g > b + 40)).sum()  # full bars: RdYlGn's top
    red = ((r > 150) & (r > g + 60) & (r > b + 60)).sum()  # YlOrRd's cells, low bars
    return green, red


def test_the_plot_is_drawn_beside_the_file_from_the_file_alone(tmp_path):
    path = tmp_path / "evaluation.json"
    path.write_text(json.dumps(evaluation(ROWS)))
    png = plot_evaluation_file(path)
    assert png == tmp_path / "evaluation.png"
    assert Image.open(png).size[0] > 1000
    green, red = _colours(png)
    assert green > 2000 and red > 300


def test_an_evaluation_without_failures_draws_no_failure_cell(tmp_path):
    path = tmp_path / "evaluation.json"
    path.write_text(json.dumps(evaluation(ROWS[:7])))
    green, red = _colours(plot_evaluation_file(path, tmp_path / "all.png"))
    assert green > 2000 and red == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["all.png", "evaluation.json"]
