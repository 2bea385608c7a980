"""The IK's own QP assembly gives mink's QP: the same objective, the position and velocity
limits' rows as bounds, the collision limit's binding rows; and the carried distance bounds
never rule out a pair that is within reach."""

import mink
import mujoco
import numpy as np
import pytest

from pyramid_sim.config import SimConfig
from pyramid_sim.core.poses import Pose
from pyramid_sim.physics import names as c
from pyramid_sim.physics.ik import DualArmIK
from pyramid_sim.physics.ik_qp import NO_BOUND

pytestmark = pytest.mark.physics


def _ik_at(
    rng: np.random.Generator, robot: str = "panda", limit_acceleration: bool = True
) -> DualArmIK:
    """An IK with both arms at random configurations within their ranges, aimed at random
    poses in front of the robot."""
    ik = DualArmIK(SimConfig(robot=robot), limit_acceleration=limit_acceleration)
    model = ik.model
    q = model.qpos0.copy()
    low, high = model.jnt_range.T
    for j in range(model.njnt):
        q[model.jnt_qposadr[j]] = rng.uniform(low[j], high[j]) if model.jnt_limited[j] else 0.0
    ik.configuration.update(q)
    for arm in c.ARMS:
        ik.set_target(
            arm,
            Pose(
                rng.uniform(0.3, 0.7),
                rng.uniform(-0.4, 0.4),
                rng.uniform(0.1, 0.4),
                rng.uniform(-np.pi, np.pi),
            ),
        )
    return ik


@pytest.mark.parametrize("robot", ["panda", "baxter"])
def test_objective_and_bounds_are_minks(robot):
    rng = np.random.default_rng(3)
    for _ in range(5):
        ik = _ik_at(rng, robot)
        mink_qp = mink.build_ik(ik.configuration, ik.task_list, ik.dt, ik.damping, ik.limits[:2])
        H, c_ = ik.problem.objective()
        np.testing.assert_allclose(H, mink_qp.P, rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(c_, mink_qp.q, rtol=1e-12, atol=1e-12)
        # mink's rows are +-unit vectors: each is one bound on one dof, and every bound is one.
        low, high = ik.problem.bounds()
        mink_low, mink_high = np.full(ik.model.nv, -NO_BOUND), np.full(ik.model.nv, NO_BOUND)
        for row, bound in zip(mink_qp.G, mink_qp.h):
            (dof,) = np.flatnonzero(row)
            if row[dof] > 0:
                mink_high[dof] = min(mink_high[dof], bound / row[dof])
            else:
                mink_low[dof] = max(mink_low[dof], bound / row[dof])
        np.testing.assert_allclose(low, mink_low, rtol=1e-12)
        np.testing.assert_allclose(high, mink_high, rtol=1e-12)


def test_collision_rows_are_minks_binding_rows_and_none_when_apart():
    ik = DualArmIK(SimConfig())
    limit = ik.limits[-1]
    seen_rows = 0
    for target in (Pose(0.5, 0.0, 0.3, 0.0), Pose(0.45, 0.05, 0.25, 0.0)):
        for arm in c.ARMS:
            ik.set_target(arm, target)
        for _ in range(120):
            ik.step()
            G, h = limit.active_rows(ik.configuration, ik.dt)
            full = limit.compute_qp_inequalities(ik.configuration, ik.dt)
            binding = np.isfinite(full.h)
            np.testing.assert_array_equal(G, full.G[binding])
            np.testing.assert_array_equal(h, full.h[binding])
            seen_rows += h.size
    assert seen_rows > 0  # the arms did come near
    for arm, y in (("left", 0.6), ("right", -0.6)):
        ik.set_target(arm, Pose(0.3, y, 0.4, 0.0))
    for _ in range(300):
        ik.step()
    assert limit.active_rows(ik.configuration, ik.dt)[1].size == 0


def test_the_qp_solution_is_minks():
    """The whole step against mink's QP solved by the same solver (acceleration bounds off,
    as mink has none)."""
    from ctypes import c_int

    import daqp

    rng = np.random.default_rng(5)
    for _ in range(5):
        ik = _ik_at(rng, limit_acceleration=False)
        qp = mink.build_ik(ik.configuration, ik.task_list, ik.dt, ik.damping, ik.limits)
        ref, _, flag, _ = daqp.solve(
            qp.P, qp.q, qp.G, qp.h, np.full(qp.h.size, -1e30), np.zeros(qp.h.size, dtype=c_int)
        )
        assert flag > 0
        np.testing.assert_allclose(ik.solve_velocity() * ik.dt, ref, atol=1e-9)


def test_carried_gaps_never_rule_out_a_pair_within_reach():
    """Both hands sent to one point and back apart: at every step the carried bounds say
    'maybe within' whenever a pair truly is, measured by brute force; and they save most of
    the exact measurements."""
    ik = DualArmIK(SimConfig())
    gaps, model, data = ik.limits[-1].gaps, ik.model, ik.configuration.data
    distance = ik.limits[-1].limit.collision_detection_distance
    fromto = np.zeros(6)
    calls = 0
    for target_y in (0.0, 0.5, 0.0):
        for arm in c.ARMS:
            ik.set_target(arm, Pose(0.5, target_y if arm == "left" else -target_y, 0.3, 0.0))
        for _ in range(150):
            ik.step()
            truth = min(
                mujoco.mj_geomDistance(model, data, int(a), int(b), 1.0, fromto)
                for a, b in zip(gaps.g1, gaps.g2)
            )
            if truth <= distance:
                assert gaps.may_be_within(data, distance)
            calls += 1
    assert gaps.measured < calls * gaps.g1.size / 4


def test_over_a_span_the_objective_is_minks_and_the_plan_keeps_the_limits():
    """A solve for four control steps: mink's objective at the span's task gains, and a plan
    whose joints move within the velocity bounds and change speed within the acceleration
    bounds at every control step, ending where the IK's configuration stands."""
    rng = np.random.default_rng(7)
    ik = _ik_at(rng)
    ik._set_span(4)
    qp = mink.build_ik(ik.configuration, ik.task_list, 4 * ik.dt, ik.damping, ik.limits[:2])
    H, c_ = ik.problem.objective()
    np.testing.assert_allclose(H, qp.P, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(c_, qp.q, rtol=1e-12, atol=1e-12)
    ik._set_span(1)
    assert ik.tasks["left"].gain == pytest.approx(0.5)

    ik = DualArmIK(SimConfig())  # from home, the hands sent apart and far: fast moves
    for arm, y in (("left", 0.55), ("right", -0.55)):
        ik.set_target(arm, Pose(0.25, y, 0.45, 1.0))
    dofs, v_max = ik.problem._velocity_dofs, ik.problem._velocity_max
    a_max = ik._max_ddq[dofs] / ik.dt**2
    q, v = [ik.q.copy()], [np.zeros(ik.model.nv)]
    plans = 0
    while len(q) < 250:  # as the loop steps: a span where granted, else one step
        if ik.may_span(4) and ik.step(4):
            plans += 1
        else:
            ik.step(1)
        while True:
            q.append(ik.q.copy())
            v.append((q[-1] - q[-2]) / ik.dt)
            if not ik.coast():
                break
        np.testing.assert_array_equal(ik.q, ik.configuration.q)
    speeds, changes = np.abs(np.array(v)[:, dofs]), np.abs(np.diff(np.array(v)[:, dofs], axis=0))
    assert plans > 30
    assert np.any(speeds.max(axis=0) >= 0.98 * v_max)  # some did run at the bound
    assert np.all(speeds <= v_max * (1 + 1e-9))
    assert np.all(changes <= a_max * ik.dt * (1 + 1e-9))


def test_a_span_is_refused_near_the_other_arm_and_nothing_moves():
    """Both hands sent to one point: once a pair is within the collision limit's reach, a
    span is refused (by `may_span` at the present speed, and by `step` itself) and a refusal
    leaves the IK where it was."""
    ik = DualArmIK(SimConfig())
    limit = ik.limits[-1]
    for arm in c.ARMS:
        ik.set_target(arm, Pose(0.5, 0.0, 0.3, 0.0))
    for _ in range(300):
        ik.step()
        if limit.active_rows(ik.configuration, ik.dt)[1].size:
            break
    else:
        pytest.fail("the arms never came within the collision limit's reach")
    q, velocity = ik.configuration.q.copy(), ik.velocity.copy()
    assert not ik.may_span(4)
    assert not ik.step(4)
    np.testing.assert_array_equal(ik.configuration.q, q)
    np.testing.assert_array_equal(ik.velocity, velocity)
    assert not ik.planned
