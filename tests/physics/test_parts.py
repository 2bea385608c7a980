"""Each part of a build's control step made alone, from a compiled scene and the parts it
talks to, without a BuildLoop: custody, dispatch, the zone watch, the stop reasons and the
readout."""

from dataclasses import replace

import mujoco
import numpy as np
import pytest

from pyramid_sim.config import SimConfig
from pyramid_sim.core.structures import StructureSpec
from pyramid_sim.core.zone import Zone
from pyramid_sim.physics import names as c
from pyramid_sim.physics.clearance import arm_geoms
from pyramid_sim.physics.custody import BrickCustody
from pyramid_sim.physics.dispatch import ArmDispatch
from pyramid_sim.physics.handles import SceneHandles
from pyramid_sim.physics.hooks import BuildHooks
from pyramid_sim.physics.ik import DualArmIK
from pyramid_sim.physics.parts import make_parts, schedule_zones, start_at_clear_poses
from pyramid_sim.physics.reach import prepare
from pyramid_sim.physics.readout import measurements
from pyramid_sim.physics.scene import build_scene, park_position
from pyramid_sim.physics.spawner import Spawner
from pyramid_sim.physics.stops import stall_reason, stop_reason
from pyramid_sim.physics.zone_watch import ZoneWatch

CONFIG = SimConfig()
PLAN = prepare(StructureSpec("pyramid-even", layers=1), CONFIG)
BRICKS = len(PLAN.bricks) + CONFIG.spare_bricks


@pytest.fixture
def scene():
    model = build_scene(CONFIG, BRICKS).model
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    handles = SceneHandles(model, CONFIG.robot_description, BRICKS)
    spawner = Spawner(
        model,
        CONFIG.robot_description,
        handles,
        PLAN.spawn,
        clearance=0.02,
        arm_clearance=0.10,
        jitter=0.0,
        seed=0,
    )
    return model, data, handles, spawner


def test_custody_alone_feeds_the_spot_from_the_magazine_in_order(scene):
    model, data, handles, spawner = scene
    custody = BrickCustody(data, handles, spawner, len(PLAN.bricks), CONFIG)
    assert custody.needs_brick() and custody.carry == {"left": None, "right": None}
    assert custody.feed_spot() == 0  # the first magazine slot, set on the spot
    q = handles.brick_qpos[0]
    assert np.allclose(data.qpos[q : q + 2], [PLAN.spawn.x, PLAN.spawn.y], atol=1e-9)
    assert spawner.current == 0  # the loop feeds the spot again only once it is picked
    assert custody.needs_brick()  # one brick on the spot, two to pick
    assert np.allclose(
        data.qpos[handles.brick_qpos[1] : handles.brick_qpos[1] + 3],
        park_position(1, CONFIG.brick.height),
    )  # the next still waits in the magazine


@pytest.mark.parametrize("in_hand", [True, False])
def test_a_brick_lifted_off_the_spot_in_a_hand_counts_as_picked_one_knocked_off_is_replaced(
    scene, in_hand
):
    """Whoever drives the arms: the feeder stops once the structure's bricks have left the
    spot in a hand (a learner's picks have no builder's grip to count), and replaces one
    that left it otherwise. The hand's reading is set here; its contacts are tested with
    the environment's `held`."""
    model, data, handles, spawner = scene
    custody = BrickCustody(data, handles, spawner, len(PLAN.bricks), CONFIG)
    left_hand: set[int] = set()
    custody.holds.slots = lambda _data: [left_hand, set()]
    for slot in range(len(PLAN.bricks)):
        assert custody.needs_brick() and custody.feed_spot() == slot
        left_hand.clear()
        if in_hand:
            left_hand.add(slot)
        q = handles.brick_qpos[slot]
        data.qpos[q + 2] += 0.3  # lifted off the spot
        mujoco.mj_forward(model, data)
        custody.notice_taken()
        assert spawner.current is None
    assert custody.picked() == (len(PLAN.bricks) if in_hand else 0)
    assert custody.needs_brick() is not in_hand  # a spare only for bricks no hand took


def test_dispatch_alone_hands_the_first_picks_out_by_the_schedule(scene):
    model, data, handles, spawner = scene
    ik = DualArmIK(CONFIG)
    start_at_clear_poses(model, data, handles, ik, CONFIG)
    tcp = {a: ik.tcp_pose(a) for a in c.ARMS}
    dispatch = ArmDispatch(PLAN, CONFIG, spawner, tcp, schedule_zones("lockstep", PLAN, CONFIG))
    assert dispatch.step_of("left") is None and dispatch.step_of("right") is None
    assert dispatch.schedule(0.0) is False  # not finished: tasks handed out
    first = {a: dispatch.task_of[a] for a in c.ARMS}
    assert all(t is not None for t in first.values())
    busy = [a for a in c.ARMS if dispatch.step_of(a) is not None]
    assert busy  # at least one arm has its first step, DE NIRO's hover
    pose = dispatch.advance(busy[0], lambda: 0.0, lambda *done: None)
    assert np.isfinite([pose.x, pose.y, pose.z]).all()


def test_the_zone_watch_alone_counts_both_arms_in_one_zone(scene):
    model, data, handles, _ = scene
    ik = DualArmIK(CONFIG)
    start_at_clear_poses(model, data, handles, ik, CONFIG)

    class Heard:
        def __init__(self):
            self.reports = []

        def report_zone(self, arm, outside, zone):
            self.reports.append((arm, outside, zone))

    heard = Heard()
    watch = ZoneWatch(schedule_zones("overlap", PLAN, CONFIG), data, handles)
    assert watch.update(heard) is False and watch.violations == 0
    assert {(a, z) for a, _, z in heard.reports} == {(a, z) for a in c.ARMS for z in watch.zones}
    assert all(outside for _, outside, _ in heard.reports)  # the clear poses are outside
    everywhere = ZoneWatch({"all": Zone(-5.0, 5.0, -5.0, 5.0)}, data, handles)
    assert everywhere.update(heard) is True and everywhere.violations == 1


def test_a_stall_reason_alone_names_what_the_arms_wait_for():
    parts = make_parts(PLAN, CONFIG)
    text = stall_reason(parts.dispatch, parts.custody, parts.spawner, CONFIG, 61.0)
    assert text == "stalled at t = 61.0 s: no arm finished a move for 60 s; arms idle"
    parts.dispatch.schedule(0.0)  # the lockstep's first phase: right to clear, left picks
    text = stall_reason(parts.dispatch, parts.custody, parts.spawner, CONFIG, 61.0)
    # The left arm may not enter the shared zone before the zone watch has seen the right
    # arm outside it, and no watch has run: it is held, and the reason names what it waits for.
    assert text == (
        "stalled at t = 61.0 s: no arm finished a move for 60 s; "
        "left arm waiting for the shared zone"
    )


def test_the_stop_reasons_alone_say_why_a_build_stops_and_nothing_before():
    parts = make_parts(PLAN, CONFIG)
    args = (parts.dispatch, parts.custody, parts.spawner, CONFIG)
    assert stop_reason(*args, now=10.0, last_progress=0.0) is None
    assert stop_reason(*args, now=61.0, last_progress=0.0).startswith("stalled at t = 61.0 s")
    late = CONFIG.max_sim_time + 1
    assert stop_reason(*args, now=late, last_progress=late) == (
        f"build did not finish within {CONFIG.max_sim_time:g} s of simulated time"
    )


def test_the_actuation_alone_ramps_the_iks_joints_and_the_gaps_over_the_substeps():
    parts = make_parts(PLAN, CONFIG)
    act, ctrl, index = parts.actuation, parts.data.ctrl, parts.handles.ctrl_index
    joints = len(parts.ik.qadr["left"])
    command = act.command([0.01, 0.02]).copy()
    assert command[[joints, 2 * joints + 1]].tolist() == [0.01, 0.02]
    assert np.array_equal(
        np.delete(command, [joints, 2 * joints + 1]),
        parts.ik.q[np.concatenate([parts.ik.qadr[a] for a in c.ARMS])],
    )  # the Panda's servos hold against gravity: no sag to aim past
    before, seen = ctrl[index].copy(), []
    hooks = BuildHooks(on_step=lambda d: seen.append(d.ctrl[index].copy()))
    assert act.step(command, hooks) == (False, CONFIG.substeps)
    assert len(seen) == CONFIG.substeps and np.allclose(seen[-1], command)
    assert np.allclose(seen[0], before + (command - before) / CONFIG.substeps)


def test_the_readout_alone_reports_the_state_it_is_given():
    parts = make_parts(PLAN, replace(CONFIG, seed=4))
    got = measurements(parts, physics_steps=0, ik_solves=0, failure="stopped by hand", wall=0.5)
    assert got.failure == "stopped by hand" and got.physics_steps == 0 and got.sim_time == 0.0
    assert got.final_pos.shape == (BRICKS, 3)
    assert np.allclose(got.final_pos[2], park_position(2, CONFIG.brick.height))  # nothing has moved
    assert got.zone_violations == 0 and got.drops == () and got.slip_mm == {}
    assert set(got.contact_friction) == {"brick_brick", "brick_table", "pad_brick"}


def test_an_ik_with_no_solution_stops_the_build_with_its_reason():
    """An IK configuration outside a joint's range leaves the QP no solution: the build stops
    at once naming it, rather than raising out of the build."""
    from pyramid_sim.output.judge import judge
    from pyramid_sim.physics.loop import BuildLoop

    loop = BuildLoop.of(PLAN, CONFIG)
    q = loop.ik.configuration.q.copy()
    shoulder = loop.ik.qadr["left"][1]
    q[shoulder] = loop.ik.q_max[shoulder] + 0.5  # the left shoulder far past its range
    loop.ik.configuration.update(q)
    result = judge(loop.run(), CONFIG)
    assert not result.success and "finished" in result.failed_checks
    assert result.failure_reason.startswith("the IK found no joint motion within the arms' limits")
    assert result.sim_time_s < 0.1
    assert result.closest_arm_approach_mm is None  # stopped before the arms were ever measured


def test_a_baxter_hand_is_dispatched_at_its_own_speed():
    config = SimConfig(robot="baxter")
    parts = make_parts(prepare(StructureSpec("pyramid-even", layers=1), config), config)
    parts.dispatch.schedule(0.0)
    speeds = [s.speed for a in c.ARMS for s in parts.dispatch.runners[a].steps if s.speed]
    assert speeds and max(speeds) == 0.3


def test_the_closest_approach_is_the_true_distance_from_the_first_look():
    """Before any look there is no closest approach; the first measures every pair exactly."""
    parts = make_parts(PLAN, CONFIG)
    assert parts.clearance.closest == float("inf") and parts.clearance.closest_time is None
    parts.clearance.update()
    model, data, robot, fromto = parts.model, parts.data, CONFIG.robot_description, np.zeros(6)
    left, right = (
        arm_geoms(model, robot.arms[a], robot.arms[a].guarded_bodies + robot.arms[a].finger_bodies)
        for a in c.ARMS
    )
    true = min(mujoco.mj_geomDistance(model, data, a, b, 10.0, fromto) for a in left for b in right)
    assert parts.clearance.closest == pytest.approx(true, abs=1e-9)
