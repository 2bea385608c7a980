"""The judge, without physics: every check of a successful build can fail, and the reason
names it. Real builds and episodes trip the meters behind the checks: a brick slides past the
slip limit in a greased grip (tests/physics/test_reliability.py), the arms meet, a joint
passes its speed or its torque limit in an episode (tests/physics/test_env.py), and a clean
build reads each above zero (tests/physics/test_build.py)."""

from dataclasses import replace

import numpy as np
import pytest

import pyramid_sim
from pyramid_sim.config import SimConfig
from pyramid_sim.output.judge import judge

CONFIG = SimConfig()


PLAN = pyramid_sim.plan("pyramid", layers=1)


def test_a_clean_build_passes_every_check(on_target):
    result = judge(on_target(PLAN), CONFIG)
    assert result.success and result.failure_reason is None and result.failed_checks == ()
    assert all(result.checks.values()) and result.slip_limit_mm == 5.0


@pytest.mark.parametrize(
    "changes, check, words",
    [
        ({"failure": "stalled at t = 70 s"}, "finished", "stalled"),
        (
            {"final_pos": np.array([[0.0, 0.0, 0.0]])},
            "bricks_in_place",
            "1 of 1 bricks not in place",
        ),
        ({"slip_mm": {0: 5.5}}, "slip", "slid 5.5 mm in the hand, over the 5 mm limit"),
        ({"arm_arm_contacts": 2}, "arm_arm_contacts", "2 arm-arm contacts"),
        ({"arm_body_contacts": 1}, "arm_body_contacts", "1 contacts of an arm with the robot's"),
        ({"zone_violations": 4}, "shared_zone", "both arms in one zone"),
        (
            {"joint_speed_ratio": 1.02, "speed_joint": 8},
            "joint_speed",
            "the right arm's joint panda_joint2 moved at 1.02 of its velocity limit (2.175 rad/s)",
        ),
        (
            {"joint_torque_ratio": 1.19},
            "joint_torque",
            "the left arm's joint panda_joint4 demanded 1.19 of its torque limit (87 N m",
        ),
        ({"finger_limit_mm": 3.0}, "finger_range", "3.00 mm past its joint range"),
        ({"idle_motion_mm": 52.0}, "idle_bricks", "nobody had touched moved 52.0 mm"),
    ],
)
def test_each_check_fails_the_build_and_is_named(changes, check, words, on_target):
    result = judge(on_target(PLAN, **changes), CONFIG)
    assert not result.success and check in result.failed_checks
    assert result.checks[check] is False
    assert words in result.failure_reason
    assert result.to_dict()["failed_checks"] == list(result.failed_checks)


def test_the_slip_limit_is_a_setting(on_target):
    strict = replace(CONFIG, slip_limit_mm=0.5)
    assert "slip" in judge(on_target(PLAN), strict).failed_checks
    with pytest.raises(pyramid_sim.ConfigError, match="slip limit"):
        replace(CONFIG, slip_limit_mm=0.0)


@pytest.mark.parametrize("limit", [30.0, 31.0, float("nan")])
def test_a_slip_limit_no_slip_can_reach_is_refused(limit, on_target):
    """A brick 30 mm out of its grip has been dropped, so no slip of 30 mm or more is ever
    measured: such a limit could never fail a build."""
    with pytest.raises(pyramid_sim.ConfigError, match=r"accepted \(0, 30\): a brick 30 mm"):
        replace(CONFIG, slip_limit_mm=limit)
    assert (
        "slip"
        in judge(
            on_target(PLAN, slip_mm={0: 29.0}), replace(CONFIG, slip_limit_mm=28.5)
        ).failed_checks
    )


def test_docs_name_every_field_a_result_writes(on_target):
    from dataclasses import fields
    from pathlib import Path

    from pyramid_sim.output.result import (
        BrickResult,
        BuildInputs,
        BuildResult,
        VideoInfo,
    )

    text = (Path(__file__).resolve().parents[1] / "docs" / "outputs.md").read_text()
    doc = judge(on_target(PLAN), CONFIG).to_dict()
    names = {*doc, *doc["bricks"][0], *doc["inputs"], *doc["checks"]}
    names |= {
        f.name for cls in (BuildResult, BrickResult, BuildInputs, VideoInfo) for f in fields(cls)
    }
    missing = sorted(n for n in names if f"`{n}`" not in text)
    assert not missing, f"docs/outputs.md does not name {missing}"


def test_a_baxter_limit_names_the_arm_the_joint_and_the_limit(on_target):
    baxter = replace(CONFIG, robot="baxter")
    reason = judge(on_target(PLAN, joint_torque_ratio=1.25, torque_joint=1), baxter).failure_reason
    assert reason.startswith(
        "the left arm's joint left_s1 demanded 1.25 of its torque limit (50 N m"
    )
