"""The waypoint mode's hands: a gap says open or closed, the hand grips and lets go on the
scripted builder's ramps, and a gap a learner leaves between open and closed still closes it."""

from types import SimpleNamespace

import pytest

from pyramid_sim.config import SimConfig
from pyramid_sim.core.primitives import Step, StepKind
from pyramid_sim.learning.action_modes.gripper_switch import GripperSwitch

DT = 0.002


def _run(switch: GripperSwitch, gap: float, seconds: float) -> list[float]:
    return [switch.command(0, gap, DT) for _ in range(round(seconds / DT))]


def test_a_gap_between_touching_and_open_closes_the_hand_with_the_grip_force():
    switch = GripperSwitch(SimConfig(), 2)
    assert switch.squeeze < switch.contact < switch.threshold < switch.open
    commands = _run(switch, switch.threshold - 0.001, switch.ramp_time + 0.05)
    assert commands[-1] == 0.0  # closed: the actuator's force limit squeezes
    ramp = commands[: round(switch.ramp_time / DT) - 1]
    assert ramp[0] < switch.open and ramp[-1] == pytest.approx(switch.squeeze, abs=1e-3)
    assert all(b < a for a, b in zip(ramp, ramp[1:], strict=False))  # slowly onto the brick
    assert switch.held(0) == 0.0 and switch.held(1) == switch.open  # the other hand untouched


def test_a_gap_at_the_threshold_or_above_lets_go_from_where_the_pads_touch():
    switch = GripperSwitch(SimConfig(), 2)
    switch.reset([0.0, switch.open])
    commands = _run(switch, switch.threshold, switch.ramp_time)
    assert commands[0] == pytest.approx(switch.contact, abs=1e-3)
    assert commands[-1] == pytest.approx(switch.open)
    assert switch.held(0) == switch.open


def _runner(kind: StepKind | None, gap: float, opening: bool = False) -> SimpleNamespace:
    step = None if kind is None else Step(kind.value, kind)
    return SimpleNamespace(current=step, gap=gap, opening=opening)


def test_the_scripted_hand_is_labelled_closed_from_a_grip_until_its_release_opens():
    switch = GripperSwitch(SimConfig(), 2)
    half = (switch.open + switch.squeeze) / 2
    assert switch.label(_runner(StepKind.GRIP, switch.open)) == 0.0  # at once, not on the ramp
    assert switch.label(_runner(StepKind.MOVE, 0.0)) == 0.0
    assert switch.label(_runner(StepKind.RELEASE, 0.0)) == 0.0
    assert switch.label(_runner(StepKind.RELEASE, half, opening=True)) == switch.open
    assert switch.label(_runner(None, switch.open)) == switch.open
