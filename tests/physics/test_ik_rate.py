"""The IK at a lower rate in free motion: a build follows a solve's plan only while each arm is
still or on a free move and no guarded pair could be within the collision limit's reach; it
solves at every control step elsewhere, and at an interval of one everywhere; `ik_solves`
counts the solves."""

from dataclasses import replace

import mink
import numpy as np
import pytest

from pyramid_sim.config import SimConfig
from pyramid_sim.core.structures import StructureSpec
from pyramid_sim.physics import names as c
from pyramid_sim.physics.ik_rate import FREE_MOVES
from pyramid_sim.physics.loop import BuildLoop
from pyramid_sim.physics.reach import prepare

pytestmark = pytest.mark.physics

SPEC = StructureSpec("pyramid-even", layers=1)


def test_plans_are_followed_only_in_free_motion_beyond_the_collision_limits_reach():
    base = SimConfig()
    config = replace(base, motion=replace(base.motion, free_ik_interval=3))
    loop = BuildLoop.of(prepare(SPEC, config), config)
    ik = loop.ik
    check = mink.Configuration(ik.model)  # mink's own limit, on a configuration of its own
    reach = ik.limits[-1].limit
    coasted = 0
    coast = ik.coast

    def checked_coast() -> bool:
        nonlocal coasted
        if not coast():
            return False
        coasted += 1
        check.update(ik.q)
        assert not np.isfinite(reach.compute_qp_inequalities(check, 1.0).h).any()
        for arm in c.ARMS:
            runner = loop.dispatch.runners[arm]
            assert (
                runner.current is None or not runner.started or runner.current.name in (FREE_MOVES)
            )
        return True

    ik.coast = checked_coast  # type: ignore[method-assign]
    measured = loop.run()
    assert measured.failure is None
    control_steps = measured.physics_steps // config.substeps
    assert coasted > control_steps // 5  # free motion is much of a build
    assert measured.ik_solves + coasted == control_steps


def test_by_default_the_ik_solves_every_control_step():
    config = SimConfig()
    measured = BuildLoop.of(prepare(SPEC, config), config).run()
    assert measured.failure is None
    assert measured.ik_solves == measured.physics_steps // config.substeps
