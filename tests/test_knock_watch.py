"""Placed bricks are watched for knocks; one taken up again to be set right is not, until it
is let go again."""

import numpy as np

from pyramid_sim.core.incidents import KNOCK_DISTANCE, KnockWatch


def test_a_brick_taken_up_again_is_no_knock_and_is_watched_again_once_let_go():
    watch = KnockWatch()
    watch.placed(0, slot=3, body=5, position=np.zeros(3))
    watch.placed(1, slot=4, body=6, position=np.ones(3))
    xpos = np.zeros((8, 3))
    xpos[6] = 1.0
    xpos[5] = (2 * KNOCK_DISTANCE, 0.0, 0.0)  # the brick in slot 3 carried away
    watch.forget(3)
    assert watch.check(xpos, 1.0) == [] and watch.bricks == [1] and watch.slots == [4]
    watch.placed(0, slot=3, body=5, position=xpos[5].copy())  # let go where it is now
    assert watch.check(xpos, 2.0) == []
    xpos[5, 0] += 2 * KNOCK_DISTANCE
    knocks = watch.check(xpos, 3.0)
    assert [(k.brick, k.slot) for k in knocks] == [(0, 3)]
