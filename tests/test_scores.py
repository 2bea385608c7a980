"""An evaluation's scores, MuJoCo-free: the Wilson interval against its closed form's known
values, failures grouped by kind, and a summary of rows."""

import pytest

from pyramid_sim.learning.evaluation.scores import failure_kind, summary, wilson_interval


@pytest.mark.parametrize(
    "wins, n, low, high",
    [
        (20, 20, 0.8389, 1.0),
        (0, 20, 0.0, 0.1611),
        (10, 20, 0.2993, 0.7007),
        (87, 100, 0.7902, 0.9224),  # about +-7 points at n = 100
    ],
)
def test_the_wilson_interval_has_its_known_values(wins, n, low, high):
    got = wilson_interval(wins, n)
    assert got == pytest.approx((low, high), abs=1e-4)


def test_no_trial_says_nothing():
    assert wilson_interval(0, 0) == (0.0, 1.0)


@pytest.mark.parametrize(
    "text, kind",
    [
        ("a joint demanded 1.13 of its torque limit", "torque limit"),
        ("a joint moved at 1.05 of its velocity limit", "speed limit"),
        ("arm-arm contact at t = 3.000 s", "arm-arm contact"),
        ("a brick (magazine slot 2) left the table", "brick off the table"),
        ("build did not finish within 600 s of simulated time", "time limit"),
        ("step limit: 2250 steps", "step limit"),
        ("something new", "other"),
        (None, None),
    ],
)
def test_each_failure_has_its_kind(text, kind):
    assert failure_kind(text) == kind


def test_a_summary_counts_what_its_rows_hold():
    rows = [
        {"success": True, "bricks_placed": 2, "failure": None, "steps": 500},
        {"success": False, "bricks_placed": 1, "failure": "step limit: 900 steps", "steps": 900},
        {
            "success": False,
            "bricks_placed": 0,
            "failure": "arm-arm contact at t = 1 s",
            "steps": 40,
        },
    ]
    s = summary(rows, bricks=2)
    assert s["episodes"] == 3 and s["successes"] == 1
    assert s["success_rate"] == pytest.approx(1 / 3)
    assert s["success_rate_95"][0] < 1 / 3 < s["success_rate_95"][1]
    assert s["bricks_placed_mean"] == 1.0
    assert s["bricks_placed_episodes"] == {"0": 1, "1": 1, "2": 1}
    assert s["failures"] == {"arm-arm contact": 1, "step limit": 1}
    assert s["episode_steps"] == {"mean": 480.0, "min": 40, "max": 900}
