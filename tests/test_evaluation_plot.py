"""The plot `evaluate` writes beside evaluation.json, drawn from the file alone: a bar an
episode coloured by the bricks it placed, and the failures' kinds against the brick they
happened on."""

import json

import numpy as np
from PIL import Image

from pyramid_sim.learning.evaluation.plot import (
    failure_grids,
    failure_sites,
    plot_evaluation_file,
)
from pyramid_sim.learning.evaluation.scores import summary


def evaluation(rows):
    scores = {"policy": "act", **summary(rows, 6), "rows": rows}
    scores["task"] = {"structure": "pyramid", "size": {"layers": 3}, "robot": "panda"}
    return scores


def row(seed, placed, failure=None, at=None):
    return {
        "seed": seed,
        "success": failure is None,
        "bricks_placed": placed,
        "failure": failure,
        "steps": 100,
        "failed_at": at,
    }


def site(brick, primitive, read="script"):
    layer = None if brick is None else brick // 3
    return {"brick": brick, "layer": layer, "arm": "left", "primitive": primitive, "read": read}


ROWS = [row(100000 + i, 6) for i in range(7)] + [
    row(100007, 2, "a joint demanded 1.20 of its torque limit", site(2, "pick servo")),
    row(100008, 2, "a joint demanded 1.31 of its torque limit", site(2, "pick servo")),
    row(100009, 4, "step limit: 4000 steps", site(4, "place release")),
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


def test_each_failure_is_placed_by_its_kind_primitive_and_brick():
    assert failure_sites(ROWS) == [
        ("torque limit", "pick servo", 2),
        ("torque limit", "pick servo", 2),
        ("step limit", "place release", 4),
    ]


def test_the_grids_count_failures_by_kind_and_by_primitive_against_the_brick():
    more = [*ROWS, row(100010, 0, "arm-arm contact at t = 1.000 s", site(0, "place hover"))]
    grids = failure_grids(more, 6)
    kinds, columns, counts = grids["kind"]
    assert kinds == ["arm-arm contact", "step limit", "torque limit"]
    assert columns == ["0", "1", "2", "3", "4", "5"]
    assert counts == [[1, 0, 0, 0, 0, 0], [0, 0, 0, 0, 1, 0], [0, 0, 2, 0, 0, 0]]
    primitives, _, counts = grids["primitive"]
    assert primitives == ["pick servo", "place hover", "place release"]  # a brick's order
    assert counts == [[0, 0, 2, 0, 0, 0], [1, 0, 0, 0, 0, 0], [0, 0, 0, 0, 1, 0]]
    assert failure_grids(ROWS[:7], 6) == {}
    waits = [
        row(1, 0, "step limit: 9 steps", site(0, p))
        for p in ("pick done, waiting", "clear", "pick waiting to enter", "place servo")
    ]
    assert failure_grids(waits, 6)["primitive"][0] == [
        "pick waiting to enter",
        "pick done, waiting",
        "place servo",
        "clear",
    ]


def test_a_file_from_before_failed_at_still_plots_its_failures(tmp_path):
    """Rows without `failed_at` (evaluations written before it): the brick after those
    placed, the primitive not recorded."""
    old = [{k: v for k, v in r.items() if k != "failed_at"} for r in ROWS]
    assert [s[1:] for s in failure_sites(old)] == [("not recorded", 2)] * 2 + [("not recorded", 4)]
    path = tmp_path / "evaluation.json"
    path.write_text(json.dumps(evaluation(old)))
    green, red = _colours(plot_evaluation_file(path))
    assert green > 2000 and red > 300


def test_a_failure_after_the_last_brick_has_a_column_of_its_own(tmp_path):
    rows = [
        row(1, 6, "arm-arm contact at t = 9.000 s", site(None, "after the last brick", "scene"))
    ]
    assert failure_sites(rows) == [("arm-arm contact", "after the last brick", None)]
    path = tmp_path / "evaluation.json"
    path.write_text(json.dumps(evaluation(rows)))
    _, red = _colours(plot_evaluation_file(path))
    assert red > 300
