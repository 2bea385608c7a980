"""The four-phase lockstep, without physics: order, barrier, exclusion."""

import pytest

from pyramid_sim import Action, LockstepScheduler


def drive(scheduler, finish_order=("left", "right")):
    """Run the scheduler to the end; returns the (phase, left, right) sequence."""
    seen = []
    while not scheduler.finished:
        left, right = scheduler.task("left"), scheduler.task("right")
        seen.append((scheduler.phase, (left.action, left.brick), (right.action, right.brick)))
        for arm in finish_order:
            scheduler.report_zone(arm, True)
        for arm in finish_order:
            scheduler.complete(arm)
    return seen


def test_four_phases_in_the_seeds_order():
    seen = drive(LockstepScheduler(left=[0, 2], right=[1, 3]))
    assert seen[:4] == [
        (1, (Action.PICK, 0), (Action.CLEAR, None)),
        (2, (Action.CLEAR, None), (Action.PICK, 1)),
        (3, (Action.PLACE, 0), (Action.CLEAR, None)),
        (4, (Action.CLEAR, None), (Action.PLACE, 1)),
    ]
    assert [s[0] for s in seen] == [1, 2, 3, 4, 1, 2, 3, 4]


def test_odd_count_skips_the_right_arms_empty_phases():
    seen = drive(LockstepScheduler(left=[0, 2], right=[1]))
    assert seen[-2:] == [
        (1, (Action.PICK, 2), (Action.CLEAR, None)),
        (3, (Action.PLACE, 2), (Action.CLEAR, None)),
    ]


def test_barrier_waits_for_both_arms():
    s = LockstepScheduler(left=[0], right=[1])
    s.complete("left")
    assert s.phase == 1  # the right arm has not finished clearing
    s.complete("right")
    assert s.phase == 2


def test_worker_enters_only_after_the_other_arm_is_outside():
    s = LockstepScheduler(left=[0], right=[1])
    s.report_zone("right", False)
    assert not s.may_enter("left")
    assert not s.may_enter("right")  # clearing arms never enter
    s.report_zone("right", True)
    assert s.may_enter("left")
    s.report_zone("right", False)
    assert not s.may_enter("left")


@pytest.mark.parametrize("finish_order", [("left", "right"), ("right", "left")])
def test_every_brick_is_picked_and_placed_once(finish_order):
    seen = drive(LockstepScheduler(left=[0, 2, 4], right=[1, 3]), finish_order)
    picks = [t[1] for _, *tasks in seen for t in tasks if t[0] is Action.PICK]
    places = [t[1] for _, *tasks in seen for t in tasks if t[0] is Action.PLACE]
    assert picks == [0, 1, 2, 3, 4]
    assert places == [0, 1, 2, 3, 4]


def test_never_two_workers_in_one_phase():
    s = LockstepScheduler(left=list(range(0, 10, 2)), right=list(range(1, 10, 2)))
    for _, left, right in drive(s):
        workers = [t for t in (left, right) if t[0] in (Action.PICK, Action.PLACE)]
        assert len(workers) == 1


def test_a_dropped_brick_is_picked_again_at_the_arms_next_pick():
    scheduler = LockstepScheduler(left=[0, 2], right=[1, 3])
    scheduler.report_zone("left", True)
    scheduler.report_zone("right", True)
    for arm in ("left", "right"):  # phase 1: left picks 0
        scheduler.complete(arm)
    assert scheduler.phase == 2
    scheduler.dropped("left", 0)  # lost while the left arm waits at its clear pose
    assert scheduler.task("left").action is Action.CLEAR
    seen = drive(scheduler)
    left_work = [s[1] for s in seen if s[1][0] is not Action.CLEAR]
    assert left_work == [(Action.PICK, 0), (Action.PLACE, 0), (Action.PICK, 2), (Action.PLACE, 2)]
    right_work = [s[2] for s in seen if s[2][0] is not Action.CLEAR]
    assert right_work == [(Action.PICK, 1), (Action.PLACE, 1), (Action.PICK, 3), (Action.PLACE, 3)]
