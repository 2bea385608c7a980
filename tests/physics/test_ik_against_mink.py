"""The IK's step is mink's: on states recorded from real builds (the arms far apart, and near
enough for the collision limit's rows to enter the QP), the velocity the IK's own QP assembly
gives equals `mink.solve_ik` on the same configuration, tasks and limits, solved by the same
solver."""

import mink
import numpy as np
import pytest

from pyramid_sim.config import SimConfig
from pyramid_sim.core.structures import StructureSpec
from pyramid_sim.physics import names as c
from pyramid_sim.physics.ik import DualArmIK
from pyramid_sim.physics.loop import BuildLoop
from pyramid_sim.physics.reach import prepare

STATES = 300
EVERY = 7  # control steps between recorded states


def _recorded_states(config: SimConfig) -> list[tuple[np.ndarray, list[mink.SE3]]]:
    """The IK's configuration and both frame targets every `EVERY` control steps of a build."""
    loop = BuildLoop.of(prepare(StructureSpec("pyramid-even", layers=2), config), config)
    states = []
    for k in range(STATES * EVERY):
        command = loop.expert_command()
        if command is None:
            break
        if k % EVERY == 0:
            ik = loop.ik
            targets = [ik.tasks[a].transform_target_to_world.copy() for a in c.ARMS]
            states.append((ik.configuration.q.copy(), targets))
        assert loop.apply(command) is None
    return states


@pytest.mark.parametrize("schedule", ["lockstep", "overlap"])
def test_the_step_is_mink_solve_ik_on_states_from_a_build(schedule):
    config = SimConfig(schedule=schedule)
    states = _recorded_states(config)
    assert len(states) == STATES
    # mink has no acceleration limit: the reference IK is solved without one too.
    ik = DualArmIK(config, limit_acceleration=False)
    collision, near, worst = ik.limits[-1], 0, 0.0
    for q, targets in states:
        ik.configuration.update(q)
        for arm, target in zip(c.ARMS, targets):
            ik.tasks[arm].set_target(target)
        ours = ik.solve_velocity()
        theirs = mink.solve_ik(
            ik.configuration, ik.task_list, ik.dt, "daqp", damping=ik.damping, limits=ik.limits
        )
        worst = max(worst, float(np.abs(ours - theirs).max()))
        near += collision.active_rows(ik.configuration, ik.dt)[1].size > 0
    assert worst < 1e-8
    if schedule == "overlap":
        assert near > 10  # states with the arms within the collision limit's reach
