"""The overlap schedule as a pure state machine: picks and places in build order, one arm in a
zone at a time, no two conflicting tasks at once, every brick built once, drops built again;
and the zones, reach gaps and standby poses it is driven with."""

import math

import pytest

from pyramid_sim import arrange, pyramid_even
from pyramid_sim.config import MotionConfig
from pyramid_sim.core.overlap import ZONE_OF, OverlapScheduler
from pyramid_sim.core.poses import Pose
from pyramid_sim.core.primitives import standby_step
from pyramid_sim.core.scheduler import Action
from pyramid_sim.core.zone import footprint_zone, overlap_zones, segment_gap

ARMS = ("left", "right")


def _run(left, right, ticks_in=3, drop=None, conflict=lambda a, b: False):
    """Drive the scheduler as the physics loop does: an arm let into its task's zone is inside
    for `ticks_in` ticks and then done; one tick later it is out (a clear takes one tick)."""
    s = OverlapScheduler(left, right, conflict=conflict)
    inside = {a: None for a in ARMS}  # the zone each arm is in
    left_ticks = {a: 0 for a in ARMS}
    picked, placed, clashes, conflicts = [], [], 0, 0
    dropped = set()
    for _ in range(10_000):
        if s.finished:
            break
        for arm in ARMS:
            for zone in s.zones:
                s.report_zone(arm, inside[arm] != zone, zone)
        for arm in ARMS:
            task = s.task(arm)
            zone = ZONE_OF.get(task.action)
            if zone is not None and inside[arm] is None:
                if s.may_enter(arm):
                    inside[arm], left_ticks[arm] = zone, ticks_in
            elif zone is not None and inside[arm] == zone:
                left_ticks[arm] -= 1
                if task.action is Action.PLACE and task.brick == drop and drop not in dropped:
                    dropped.add(drop)
                    s.dropped(arm, drop)
                elif left_ticks[arm] == 0:
                    (picked if task.action is Action.PICK else placed).append(task.brick)
                    s.complete(arm)
            else:  # done in the zone (or clearing): out it goes
                inside[arm] = None
                if task.action is Action.CLEAR:
                    s.complete(arm)
        clashes += inside["left"] is not None and inside["left"] == inside["right"]
        tasks = [s.task(a) for a in ARMS]
        conflicts += all(inside[a] is not None for a in ARMS) and conflict(*tasks)
    return s, picked, placed, clashes, conflicts


def test_picks_and_places_follow_the_build_order_one_arm_in_a_zone():
    order = arrange(pyramid_even(4))
    left = [b.index for b in order if b.arm == "left"]
    right = [b.index for b in order if b.arm == "right"]
    s, picked, placed, clashes, _ = _run(left, right)
    assert s.finished and picked == placed == list(range(20)) and clashes == 0


def test_the_arms_work_at_once_in_different_zones():
    """Without conflicts one arm picks while the other places: the whole build takes fewer
    ticks than one arm doing everything in turn."""
    s = OverlapScheduler([0, 2], [1, 3])
    s.report_zone("right", True, "spot")
    assert s.may_enter("left")  # left picks brick 0
    s.report_zone("left", False, "spot")
    s.complete("left")  # picked: now it places brick 0
    s.report_zone("left", True, "spot")  # and has left the spot
    s.report_zone("right", True, "structure")
    assert s.may_enter("left") and s.task("left").action is Action.PLACE
    s.report_zone("left", False, "structure")
    assert s.may_enter("right") and s.task("right").action is Action.PICK  # brick 1, meanwhile


def test_conflicting_tasks_never_run_at_once():
    left, right = [0, 2, 4], [1, 3, 5]
    s, _, placed, clashes, conflicts = _run(left, right, conflict=lambda a, b: True)
    assert s.finished and placed == list(range(6)) and clashes == 0 and conflicts == 0


def test_a_zone_waits_for_the_lowest_brick_and_for_the_other_arm_to_leave():
    s = OverlapScheduler([0], [1])
    s.report_zone("left", False, "spot")  # the left arm is in the spot's zone
    assert not s.may_enter("right")  # brick 1 is not the lowest not picked, and left is in
    s.report_zone("left", True, "spot")
    assert not s.may_enter("right")  # still not its turn
    assert s.may_enter("left") and s.holder("spot") == "left"
    s.complete("left")  # picked brick 0
    assert not s.may_enter("right")  # the spot is held until the left arm is seen out
    s.report_zone("left", True, "spot")
    assert s.holder("spot") is None and s.may_enter("right")


@pytest.mark.parametrize("left, right", [([0, 1, 2], []), ([], [0, 1]), ([1, 3], [0, 2, 4])])
def test_one_arm_or_uneven_queues_finish_and_idle_after_clearing(left, right):
    s, picked, placed, clashes, _ = _run(left, right)
    assert s.finished and placed == sorted(left + right) and clashes == 0
    assert all(s.task(a).action is Action.IDLE for a in ARMS)


def test_a_dropped_brick_is_picked_and_placed_again():
    s, picked, placed, clashes, _ = _run([0, 2], [1, 3], drop=2)
    assert placed == [0, 1, 2, 3] and picked.count(2) == 2 and clashes == 0


def test_zones_follow_each_bricks_footprint_turned_by_its_yaw():
    along = footprint_zone([Pose(0.5, 0.0, 0.1, 0.0)], 0.2, 0.1, 0.01)
    across = footprint_zone([Pose(0.5, 0.0, 0.1, math.pi / 2)], 0.2, 0.1, 0.01)
    assert along.x_max - along.x_min == pytest.approx(0.22)
    assert along.y_max - along.y_min == pytest.approx(0.12)
    assert across.x_max - across.x_min == pytest.approx(0.12)
    zones = overlap_zones(
        Pose(0.49, 0.01, 0.11, math.pi / 2),
        [Pose(0.73, y, 0.11, 0.0) for y in (-0.3, 0.0, 0.3)],
        0.192,
        0.086,
        0.04,
    )
    spot, structure = zones["spot"], zones["structure"]
    assert spot.x_max < structure.x_min  # apart: an arm may pick while the other places
    assert not spot.contains((0.73, 0.0)) and structure.contains((0.73, 0.3))


def test_reach_gap_seen_from_above():
    assert segment_gap((0, 0), (1, 1), (0, 1), (1, 0)) == 0.0  # crossing
    assert segment_gap((0, 0), (1, 0), (0, 0.3), (1, 0.3)) == pytest.approx(0.3)  # parallel
    assert segment_gap((0, 0), (1, 0), (2, 1), (3, 1)) == pytest.approx(math.hypot(1, 1))
    # The Panda pair: a place near the middle crosses close to the other arm picking.
    assert segment_gap((0.15, -0.25, 0), (0.732, -0.048), (0.15, 0.25, 0), (0.49, 0.01)) < 0.15


def test_standby_waits_outside_every_zone_across_its_line_on_the_arms_side():
    zones = overlap_zones(
        Pose(0.49, 0.01, 0.11, math.pi / 2),
        [Pose(0.73, y, 0.11, 0.0) for y in (-0.3, 0.3)],
        0.192,
        0.086,
        0.04,
    )
    at = Pose(0.49, 0.01, 0.22, 1.0)
    for arm, sign in (("left", 1), ("right", -1)):
        step = standby_step(arm, list(zones.values()), 0.49, at, MotionConfig(), 0.1)
        assert step.pose is not None and not step.enters_zone
        assert not any(z.contains((step.pose.x, step.pose.y)) for z in zones.values())
        assert sign * step.pose.y > 0.2 and step.pose.z == at.z and step.pose.yaw == at.yaw


def test_zones_that_meet_become_one_box_for_both():
    zones = overlap_zones(
        Pose(0.49, 0.01, 0.11, 0.0),
        [Pose(0.6, 0.1, 0.11, 0.0), Pose(0.8, 0.3, 0.11, 0.0)],
        0.192,
        0.086,
        0.04,
    )
    assert zones["spot"] == zones["structure"]
    assert zones["spot"].contains((0.49, 0.01)) and zones["spot"].contains((0.8, 0.3))
