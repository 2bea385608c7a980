"""The overlap schedule as a pure state machine: bricks in build order, never both arms in the
zone, every brick built once, drops built again."""


import pytest

from pyramid_sim import arrange, pyramid_even
from pyramid_sim.core.overlap import OverlapScheduler
from pyramid_sim.core.scheduler import Action


def _run(left, right, ticks_in=3, drop=None):
    """Drive the scheduler as the physics loop does: a BUILD takes `ticks_in` ticks inside the
    zone once allowed, a CLEAR one more tick inside, then the arm is out."""
    s = OverlapScheduler(left, right)
    inside = {"left": False, "right": False}
    left_ticks = {"left": 0, "right": 0}
    placed, both_in = [], 0
    dropped = set()
    for _ in range(10_000):
        if s.finished:
            break
        for arm in ("left", "right"):
            s.report_zone(arm, not inside[arm])
        for arm in ("left", "right"):
            task = s.task(arm)
            if task.action is Action.BUILD and not inside[arm] and s.may_enter(arm):
                inside[arm], left_ticks[arm] = True, ticks_in
            elif task.action is Action.BUILD and inside[arm]:
                left_ticks[arm] -= 1
                if drop is not None and task.brick == drop and drop not in dropped:
                    dropped.add(drop)
                    s.dropped(arm, drop)
                elif left_ticks[arm] == 0:
                    placed.append(task.brick)
                    s.complete(arm)
            elif task.action is Action.CLEAR:
                inside[arm] = False
                s.complete(arm)
        both_in += inside["left"] and inside["right"]
    return s, placed, both_in


def test_bricks_are_placed_in_build_order_one_arm_in_the_zone_at_a_time():
    order = arrange(pyramid_even(4))
    left = [b.index for b in order if b.arm == "left"]
    right = [b.index for b in order if b.arm == "right"]
    s, placed, both_in = _run(left, right)
    assert s.finished and placed == list(range(20)) and both_in == 0


@pytest.mark.parametrize("left, right", [([0, 1, 2], []), ([], [0, 1]), ([1, 3], [0, 2, 4])])
def test_one_arm_or_uneven_queues_finish(left, right):
    s, placed, both_in = _run(left, right)
    assert s.finished and placed == sorted(left + right) and both_in == 0
    assert all(s.task(a).action is Action.IDLE for a in ("left", "right"))


def test_a_dropped_brick_is_built_again_before_the_next():
    s, placed, both_in = _run([0, 2], [1, 3], drop=2)
    assert placed == [0, 1, 2, 3] and both_in == 0


def test_the_zone_is_refused_while_the_other_arm_is_in_it_or_holds_it():
    s = OverlapScheduler([0], [1])
    s.report_zone("left", True)
    s.report_zone("right", False)  # the right arm is in the zone
    assert not s.may_enter("left")
    s.report_zone("right", True)
    assert s.may_enter("left")  # the lowest brick, the zone free: granted, and held
    assert not s.may_enter("right")  # not its turn, and the left arm holds the zone
    s.report_zone("left", False)
    s.complete("left")  # built brick 0: now it leaves
    assert s.task("left").action is Action.CLEAR and not s.may_enter("right")
    s.report_zone("left", True)  # out: the zone is free for brick 1
    assert s.may_enter("right")
